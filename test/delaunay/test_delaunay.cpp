#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "delaunay.h"
#include "mesh.h"
#include "predicates.h"
#include "test_support.h"

using ddt::kNone;
using ddt::kPositionOne;
using ddt::Mesh;
using ddt::Position;

namespace {

// A triangle as its vertex ids, in positive order, the smallest first.
using Corners = std::array<uint32_t, 3>;

Corners canonicalCorners(uint32_t a, uint32_t b, uint32_t c) {
    if (b < a && b < c) return {b, c, a};
    if (c < a && c < b) return {c, a, b};
    return {a, b, c};
}

// A point at pixel (x, y), in fixed point.
Position pixel(int32_t x, int32_t y) { return {x * kPositionOne, y * kPositionOne}; }

// The points in row-major order (by y, then x), each once: the form delaunayOfPoints takes.
std::vector<Position> rowMajor(std::vector<Position> points) {
    std::sort(points.begin(), points.end(), [](Position p, Position q) { return p.y != q.y ? p.y < q.y : p.x < q.x; });
    points.erase(std::unique(points.begin(), points.end()), points.end());
    return points;
}

// The smallest frame (in pixels) that holds the points.
Mesh triangulate(const std::vector<Position>& points) {
    int32_t right = 0, bottom = 0;
    for (const Position& p : points) {
        right = std::max(right, p.x);
        bottom = std::max(bottom, p.y);
    }
    return ddt::delaunayOfPoints(uint32_t(right / kPositionOne + 2), uint32_t(bottom / kPositionOne + 2), points);
}

// The mesh's triangles, each read from the records of all three of its edges: every triangle
// must be named exactly three times.
std::map<Corners, int> namedTriangles(const Mesh& mesh) {
    std::map<Corners, int> named;
    for (const ddt::EdgeVertices& v : mesh.vertices) {
        if (v.l != kNone) ++named[canonicalCorners(v.a, v.b, v.l)];
        if (v.r != kNone) ++named[canonicalCorners(v.b, v.a, v.r)];
    }
    return named;
}

std::vector<Corners> trianglesOf(const Mesh& mesh) {
    std::vector<Corners> triangles;
    for (const auto& [corners, count] : namedTriangles(mesh)) triangles.push_back(corners);
    return triangles;  // sorted: a map's keys
}

// The Delaunay triangles by definition: every positive triple whose circumcircle holds no other
// point under the perturbed predicate. O(n^4), for a dozen points.
std::vector<Corners> bruteForceTriangles(const std::vector<Position>& points) {
    const uint32_t n = uint32_t(points.size());
    std::vector<Corners> triangles;
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t j = i + 1; j < n; ++j) {
            for (uint32_t k = j + 1; k < n; ++k) {
                const int64_t o = ddt::orient(points[i], points[j], points[k]);
                if (o == 0) continue;
                const uint32_t a = i, b = o > 0 ? j : k, c = o > 0 ? k : j;
                bool empty = true;
                for (uint32_t d = 0; d < n && empty; ++d)
                    if (d != a && d != b && d != c && ddt::inCircle(points[a], points[b], points[c], points[d]))
                        empty = false;
                if (empty) triangles.push_back(canonicalCorners(a, b, c));
            }
        }
    }
    std::sort(triangles.begin(), triangles.end());
    return triangles;
}

// A check of a triangulation of the convex hull of `vertex_count` used vertices, independent of
// core's checkMesh: edges in canonical order (a < b, sorted by (a, b)), each with a positive
// triangle on at least one side and neighbour links that join the right vertices, every
// triangle named by its three edges, every vertex used, Euler's V − E + F = 1 for a disk, and
// every point on the inner side of (or on) each boundary edge. Returns "" or the first problem.
std::string hullTriangulationProblem(const Mesh& mesh, uint32_t vertex_count) {
    std::vector<uint64_t> keys;
    for (const ddt::EdgeVertices& v : mesh.vertices) keys.push_back(uint64_t(v.a) << 32 | v.b);
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
        if (mesh.vertices[e].a >= mesh.vertices[e].b || mesh.vertices[e].b >= mesh.vertexCount())
            return "edge " + std::to_string(e) + ": main vertices not a < b < vertexCount";
        if (e > 0 && keys[e - 1] >= keys[e]) return "edge " + std::to_string(e) + ": not in canonical order";
    }
    auto edgeId = [&](uint32_t p, uint32_t q) {
        const uint64_t key = uint64_t(std::min(p, q)) << 32 | std::max(p, q);
        const auto found = std::lower_bound(keys.begin(), keys.end(), key);
        return found != keys.end() && *found == key ? uint32_t(found - keys.begin()) : kNone;
    };
    std::vector<Position> positions;
    std::vector<bool> used(mesh.vertexCount(), false);
    for (const ddt::EdgeVertices& v : mesh.vertices) used[v.a] = used[v.b] = true;
    for (uint32_t p = 0; p < mesh.vertexCount(); ++p)
        if (used[p]) positions.push_back(ddt::positionOf(mesh, p));
    if (positions.size() != vertex_count) return "not every vertex is used";

    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
        const ddt::EdgeVertices& v = mesh.vertices[e];
        const ddt::EdgeNeighbours& n = mesh.neighbours[e];
        const std::string name = "edge " + std::to_string(e) + ": ";
        if (v.l == kNone && v.r == kNone) return name + "no triangle";
        const Position a = ddt::positionOf(mesh, v.a), b = ddt::positionOf(mesh, v.b);
        if (v.l != kNone) {
            if (ddt::orient(a, b, ddt::positionOf(mesh, v.l)) <= 0) return name + "left triangle not positive";
            if (n.bl != edgeId(v.b, v.l) || n.la != edgeId(v.l, v.a)) return name + "wrong left neighbours";
        } else if (n.bl != kNone || n.la != kNone) {
            return name + "left neighbours without a left triangle";
        }
        if (v.r != kNone) {
            if (ddt::orient(b, a, ddt::positionOf(mesh, v.r)) <= 0) return name + "right triangle not positive";
            if (n.ar != edgeId(v.a, v.r) || n.rb != edgeId(v.r, v.b)) return name + "wrong right neighbours";
        } else if (n.ar != kNone || n.rb != kNone) {
            return name + "right neighbours without a right triangle";
        }
        if (v.l == kNone || v.r == kNone) {  // a boundary edge: no point beyond its line
            const Position p = v.l != kNone ? a : b, q = v.l != kNone ? b : a;
            for (const Position& s : positions)
                if (ddt::orient(p, q, s) < 0) return name + "a point lies beyond this boundary edge";
        }
    }
    const std::map<Corners, int> named = namedTriangles(mesh);
    for (const auto& [corners, count] : named)
        if (count != 3) return "a triangle is not named by exactly three edges";
    if (int64_t(vertex_count) - int64_t(mesh.edgeCount()) + int64_t(named.size()) != 1) return "Euler count is not 1";
    return "";
}

// Every check at once, for a triangulation of `points` (checkMesh only for frames small
// enough for its area bookkeeping).
void requireValidDelaunay(const Mesh& mesh, uint32_t vertex_count) {
    REQUIRE(hullTriangulationProblem(mesh, vertex_count) == "");
    if (uint64_t(mesh.width) * mesh.height <= (1u << 24)) REQUIRE(ddt::checkMesh(mesh, ddt::MeshHull::convex) == "");
    REQUIRE(ddt::checkDelaunay(mesh) == "");
}

// Records equal, positions aside.
bool sameEdges(const Mesh& x, const Mesh& y) {
    Mesh x_records = x, y_records = y;
    x_records.positions.clear();
    y_records.positions.clear();
    return ddt::test::sameRecords(x_records, y_records);
}

// The integer points on the circle of radius 5^k · scale about `centre`: the Gaussian integers
// u · (2 + i)^j · (2 − i)^(2k − j) have norm 5^(2k), for j = 0 … 2k and the four units u.
std::vector<Position> circlePoints(Position centre, int k, int64_t scale) {
    struct Gaussian {
        int64_t re, im;
        Gaussian times(int64_t x, int64_t y) const { return {re * x - im * y, re * y + im * x}; }
    };
    std::vector<Position> points;
    for (int j = 0; j <= 2 * k; ++j) {
        Gaussian z = {1, 0};
        for (int m = 0; m < 2 * k; ++m) z = z.times(2, m < j ? 1 : -1);
        for (int u = 0; u < 4; ++u) {
            points.push_back({int32_t(centre.x + scale * z.re), int32_t(centre.y + scale * z.im)});
            z = z.times(0, 1);
        }
    }
    return rowMajor(points);
}

// The in-circle determinant by a different road: the 4 × 4 determinant of the rows
// (x, y, x² + y², 1), untranslated, summed over all 24 permutations (Leibniz). Terms below
// 2^26 · 2^26 · 2^53 = 2^105, their sum below 2^110: exact in __int128.
__int128 referenceInCircle(Position a, Position b, Position c, Position d) {
    __int128 m[4][4];
    const Position rows[4] = {a, b, c, d};
    for (int i = 0; i < 4; ++i) {
        const __int128 x = rows[i].x, y = rows[i].y;
        m[i][0] = x;
        m[i][1] = y;
        m[i][2] = x * x + y * y;
        m[i][3] = 1;
    }
    int permutation[4] = {0, 1, 2, 3};
    __int128 sum = 0;
    do {
        int inversions = 0;
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) inversions += permutation[i] > permutation[j];
        __int128 term = 1;
        for (int i = 0; i < 4; ++i) term *= m[i][permutation[i]];
        sum += inversions % 2 ? -term : term;
    } while (std::next_permutation(permutation, permutation + 4));
    return sum;
}

}  // namespace

TEST_CASE("delaunay: a unit square is cut along (0,0)-(1,1), as the grid is", "[delaunay]") {
    //   0 ---- 1       y grows downwards; corner 1 = (1, 0) has the highest priority
    //   | \    |       (largest x − y), so the diagonal avoids it: 0–3.
    //   |   \  |
    //   2 ---- 3
    const std::vector<Position> square = {pixel(0, 0), pixel(1, 0), pixel(0, 1), pixel(1, 1)};
    const Mesh mesh = ddt::delaunayOfPoints(2, 2, square);
    CHECK(trianglesOf(mesh) == std::vector<Corners>{{0, 1, 3}, {0, 3, 2}});
    CHECK(sameEdges(mesh, ddt::buildGridMesh(2, 2)));
    CHECK(mesh.positions == square);
    const Mesh by_pixels = ddt::delaunayOfPixels(2, 2, {0, 1, 2, 3});
    CHECK(by_pixels.positions.empty());
    CHECK(ddt::test::sameRecords(by_pixels, ddt::buildGridMesh(2, 2)));
    // The rule behind it: in every cell the highest-priority corner is (x + 1, y).
    for (int32_t x = -3; x <= 3; ++x) {
        for (int32_t y = -3; y <= 3; ++y) {
            const Position p00 = pixel(x, y), p10 = pixel(x + 1, y), p01 = pixel(x, y + 1), p11 = pixel(x + 1, y + 1);
            CHECK(ddt::outranks(p10, p00));
            CHECK(ddt::outranks(p10, p01));
            CHECK(ddt::outranks(p10, p11));
        }
    }
}

TEST_CASE("delaunay: a point inside a triangle gives three triangles", "[delaunay]") {
    //   0 ------------- 1
    //   | \          /
    //   |   \      /
    //   |     2  /         2 = (2, 2) inside the hull 0 = (0, 0), 1 = (8, 0), 3 = (0, 8)
    //   |    |  /
    //   |   | /
    //   |  |/
    //   3
    const std::vector<Position> points = {pixel(0, 0), pixel(8, 0), pixel(2, 2), pixel(0, 8)};
    const Mesh mesh = triangulate(points);
    requireValidDelaunay(mesh, 4);
    CHECK(trianglesOf(mesh) == std::vector<Corners>{{0, 1, 2}, {0, 2, 3}, {1, 3, 2}});
    CHECK(mesh.edgeCount() == 6);
}

TEST_CASE("delaunay: points collinear with a hull edge split it", "[delaunay]") {
    //   0 --- 1 --- 2 --- 3        four points on y = 0, one below: the line's three
    //    \     \   /     /         segments are hull edges, each with one triangle to 4
    //      \    \ /    /
    //        --- 4 ---
    const std::vector<Position> points = {pixel(0, 0), pixel(2, 0), pixel(4, 0), pixel(6, 0), pixel(3, 4)};
    const Mesh mesh = triangulate(points);
    requireValidDelaunay(mesh, 5);
    CHECK(trianglesOf(mesh) == std::vector<Corners>{{0, 1, 4}, {1, 2, 4}, {2, 3, 4}});
    for (uint32_t i = 0; i < 3; ++i) {
        const uint32_t e = ddt::test::edgeBetween(mesh, i, i + 1);
        REQUIRE(e != kNone);
        CHECK(mesh.vertices[e].l == 4);  // (i, i + 1, 4) is positive: the left triangle
        CHECK(mesh.vertices[e].r == kNone);
    }

    // A long run first (the first points along the insertion order are collinear), the one
    // point off the line at either end or in the middle: a fan from it.
    for (const int32_t apex_x : {0, 17, 39}) {
        std::vector<Position> line;
        for (int32_t x = 0; x < 40; ++x) line.push_back(pixel(x, 0));
        line.push_back(pixel(apex_x, 3));
        const Mesh fan = triangulate(line);
        requireValidDelaunay(fan, 41);
        std::vector<Corners> expected;
        for (uint32_t i = 0; i + 1 < 40; ++i) expected.push_back({i, i + 1, 40});
        CHECK(trianglesOf(fan) == expected);
    }
    // Collinear points outside the hull on both sides, and on its edges.
    const std::vector<Position> cross =
        rowMajor({pixel(5, 0), pixel(5, 1), pixel(5, 2), pixel(5, 3), pixel(5, 4), pixel(0, 2), pixel(1, 2),
                  pixel(9, 2), pixel(10, 2), pixel(3, 2), pixel(7, 2)});
    const Mesh crossed = triangulate(cross);
    requireValidDelaunay(crossed, uint32_t(cross.size()));
    CHECK(trianglesOf(crossed) == bruteForceTriangles(cross));
}

TEST_CASE("delaunay: a cocircular octagon is cut by the priority order", "[delaunay]") {
    // The points at (±5, 0), (0, ±5), (±3, ±4) about pixel (6, 6), ids in row-major order:
    //
    //                 0
    //          1             2
    //
    //     3                       4
    //
    //          5             6
    //                 7
    //
    // All cocircular: the perturbation raises the highest-priority point most, so it is cut off
    // as an ear first: 2, then 4 (ties with 0 on x − y, larger x), 0, 1, 6, leaving (3, 5, 7).
    const std::vector<Position> octagon = {pixel(6, 1), pixel(3, 2), pixel(9, 2), pixel(1, 6),
                                           pixel(11, 6), pixel(3, 10), pixel(9, 10), pixel(6, 11)};
    REQUIRE(rowMajor(octagon) == octagon);
    const Mesh mesh = triangulate(octagon);
    requireValidDelaunay(mesh, 8);
    const std::vector<Corners> expected = {{0, 2, 4}, {0, 4, 6}, {0, 6, 1}, {1, 6, 3}, {3, 6, 7}, {3, 7, 5}};
    CHECK(trianglesOf(mesh) == expected);
    CHECK(bruteForceTriangles(octagon) == expected);

    // The twelve integer points of the same circle, and with its centre.
    std::vector<Position> twelve = octagon;
    for (auto [dx, dy] : {std::pair{4, 3}, {4, -3}, {-4, 3}, {-4, -3}}) twelve.push_back(pixel(6 + dx, 6 + dy));
    twelve = rowMajor(twelve);
    const Mesh twelve_mesh = triangulate(twelve);
    requireValidDelaunay(twelve_mesh, 12);
    CHECK(trianglesOf(twelve_mesh).size() == 10);
    CHECK(trianglesOf(twelve_mesh) == bruteForceTriangles(twelve));
    std::vector<Position> centred = twelve;
    centred.push_back(pixel(6, 6));
    centred = rowMajor(centred);
    const Mesh centred_mesh = triangulate(centred);
    requireValidDelaunay(centred_mesh, 13);
    CHECK(trianglesOf(centred_mesh).size() == 12);  // a fan from the centre
    CHECK(trianglesOf(centred_mesh) == bruteForceTriangles(centred));
}

TEST_CASE("delaunay: small sets match the brute force", "[delaunay]") {
    std::mt19937 rng(7);
    int compared = 0;
    for (int seed = 0; seed < 400; ++seed) {
        const uint32_t count = 3 + seed % 10;  // 3 … 12
        std::vector<Position> points;
        if (seed % 2 == 0) {
            // Anywhere in a 30 × 30 frame, at 1/1024 pixel.
            std::uniform_int_distribution<int32_t> coordinate(0, 29 * kPositionOne);
            for (uint32_t i = 0; i < count; ++i) points.push_back({coordinate(rng), coordinate(rng)});
        } else {
            // Pixel centres of a 5 × 5 grid: collinear triples and cocircular quadruples abound.
            std::uniform_int_distribution<int32_t> coordinate(0, 4);
            for (uint32_t i = 0; i < count; ++i) points.push_back(pixel(coordinate(rng), coordinate(rng)));
        }
        points = rowMajor(points);
        if (!ddt::delaunayInputProblem(points).empty()) continue;
        INFO("seed " << seed << ", " << points.size() << " points");
        const Mesh mesh = triangulate(points);
        requireValidDelaunay(mesh, uint32_t(points.size()));
        CHECK(trianglesOf(mesh) == bruteForceTriangles(points));
        ++compared;
    }
    CHECK(compared > 300);
}

TEST_CASE("delaunay: random sets are valid Delaunay triangulations", "[delaunay]") {
    std::mt19937 rng(11);
    SECTION("uniform, 1 000 and 20 000 points") {
        for (const uint32_t count : {1000u, 20000u}) {
            std::uniform_int_distribution<int32_t> coordinate(0, 999 * kPositionOne);
            std::vector<Position> points(count);
            for (Position& p : points) p = {coordinate(rng), coordinate(rng)};
            points = rowMajor(points);
            const Mesh mesh = ddt::delaunayOfPoints(1000, 1000, points);
            requireValidDelaunay(mesh, uint32_t(points.size()));
        }
    }
    SECTION("uniform over the largest frame") {
        std::uniform_int_distribution<int32_t> coordinate(0, int32_t(ddt::kMaxDelaunaySide - 1) * kPositionOne);
        std::vector<Position> points(5000);
        for (Position& p : points) p = {coordinate(rng), coordinate(rng)};
        points.push_back({0, 0});
        points.push_back({int32_t(ddt::kMaxDelaunaySide - 1) * kPositionOne, int32_t(ddt::kMaxDelaunaySide - 1) * kPositionOne});
        points = rowMajor(points);
        const Mesh mesh = ddt::delaunayOfPoints(ddt::kMaxDelaunaySide, ddt::kMaxDelaunaySide, points);
        requireValidDelaunay(mesh, uint32_t(points.size()));
    }
    SECTION("Gaussian clusters") {
        std::vector<Position> points;
        std::uniform_real_distribution<double> centre(100, 900);
        for (int cluster = 0; cluster < 8; ++cluster) {
            const double cx = centre(rng), cy = centre(rng);
            std::normal_distribution<double> x(cx, 5 + 10 * cluster), y(cy, 5 + 10 * cluster);
            for (int i = 0; i < 1000; ++i) {
                const double px = std::clamp(x(rng), 0.0, 999.0), py = std::clamp(y(rng), 0.0, 999.0);
                points.push_back({int32_t(px * kPositionOne), int32_t(py * kPositionOne)});
            }
        }
        points = rowMajor(points);
        const Mesh mesh = ddt::delaunayOfPoints(1000, 1000, points);
        requireValidDelaunay(mesh, uint32_t(points.size()));
    }
    SECTION("a lattice, duplicates removed") {
        std::uniform_int_distribution<int32_t> coordinate(0, 59);
        std::vector<Position> points;
        for (int i = 0; i < 3000; ++i) points.push_back(pixel(coordinate(rng), coordinate(rng)));
        points = rowMajor(points);
        REQUIRE(points.size() < 3000);
        const Mesh mesh = ddt::delaunayOfPoints(60, 60, points);
        requireValidDelaunay(mesh, uint32_t(points.size()));
    }
    SECTION("two crossing lines: hull edges split many times, fans of high degree") {
        std::vector<Position> points;
        for (int32_t x = 0; x < 2000; ++x) {
            points.push_back({x * 512, 7 * kPositionOne});  // y = 7 pixels
            points.push_back({x * 512, x * 256});           // y = x / 2
        }
        points = rowMajor(points);
        REQUIRE(points.size() == 3999);  // one point on both
        const Mesh mesh = ddt::delaunayOfPoints(1001, 501, points);
        requireValidDelaunay(mesh, 3999);
    }
    SECTION("all integer points of a circle, then with its centre") {
        const Position centre = {20000, 20000};
        std::vector<Position> points = circlePoints(centre, 5, 1);  // radius 5^5 = 3125
        REQUIRE(points.size() == 44);
        const Mesh ring = ddt::delaunayOfPoints(40, 40, points);
        requireValidDelaunay(ring, 44);
        CHECK(ring.edgeCount() == 2 * 44 - 3);  // a convex polygon: n hull edges, n − 3 diagonals
        points.push_back(centre);
        points = rowMajor(points);
        const Mesh wheel = ddt::delaunayOfPoints(40, 40, points);
        requireValidDelaunay(wheel, 45);
        CHECK(wheel.edgeCount() == 2 * 44);  // the centre sees every hull vertex: a wheel
    }
}

TEST_CASE("delaunay: known pixels triangulate as their positions do", "[delaunay]") {
    std::mt19937 rng(3);
    for (const double density : {0.05, 0.5, 0.95}) {
        const uint32_t width = 40, height = 30;
        std::bernoulli_distribution keep(density);
        std::vector<uint32_t> ids;
        for (uint32_t v = 0; v < width * height; ++v)
            if (keep(rng)) ids.push_back(v);
        std::vector<Position> points;
        for (uint32_t v : ids) points.push_back(ddt::gridPosition(v, width));
        REQUIRE(ddt::delaunayInputProblem(points) == "");
        INFO("density " << density);
        const Mesh by_pixels = ddt::delaunayOfPixels(width, height, ids);
        CHECK(by_pixels.positions.empty());
        CHECK(by_pixels.width == width);
        CHECK(by_pixels.height == height);
        requireValidDelaunay(by_pixels, uint32_t(ids.size()));
        // The same mesh through explicit positions, its vertex ids mapped back to pixel ids.
        Mesh by_points = ddt::delaunayOfPoints(width, height, points);
        for (ddt::EdgeVertices& v : by_points.vertices) {
            v.a = ids[v.a];
            v.b = ids[v.b];
            if (v.l != kNone) v.l = ids[v.l];
            if (v.r != kNone) v.r = ids[v.r];
        }
        CHECK(sameEdges(by_pixels, by_points));
    }
}

TEST_CASE("delaunay: the full grid is buildGridMesh, record for record", "[delaunay]") {
    for (auto [width, height] : {std::pair{2u, 2u}, {3u, 5u}, {17u, 9u}, {64u, 64u}}) {
        INFO(width << "x" << height);
        std::vector<uint32_t> ids(width * height);
        for (uint32_t v = 0; v < ids.size(); ++v) ids[v] = v;
        const Mesh mesh = ddt::delaunayOfPixels(width, height, ids);
        CHECK(ddt::test::sameRecords(mesh, ddt::buildGridMesh(width, height)));
        CHECK(ddt::checkDelaunay(mesh) == "");
    }
}

TEST_CASE("delaunay: checkDelaunay finds an edge that is not locally Delaunay", "[delaunay]") {
    // The unit square with the other diagonal, 1–2: the tie-break wants 0–3.
    Mesh square = ddt::buildGridMesh(2, 2);
    REQUIRE(ddt::checkDelaunay(square) == "");
    const uint32_t diagonal = ddt::test::edgeBetween(square, 0, 3);
    ddt::flipEdge(square, diagonal);
    CHECK(ddt::checkDelaunay(square) != "");

    // Any flip of a strictly convex quadrilateral in a Delaunay triangulation breaks it: the
    // triangulation is unique.
    std::mt19937 rng(5);
    std::uniform_int_distribution<int32_t> coordinate(0, 99 * kPositionOne);
    std::vector<Position> points(300);
    for (Position& p : points) p = {coordinate(rng), coordinate(rng)};
    points = rowMajor(points);
    const Mesh mesh = ddt::delaunayOfPoints(100, 100, points);
    REQUIRE(ddt::checkDelaunay(mesh) == "");
    int flipped = 0;
    for (uint32_t e = 0; e < mesh.edgeCount() && flipped < 20; e += 7) {
        const ddt::EdgeVertices v = mesh.vertices[e];
        if (v.l == kNone || v.r == kNone) continue;
        const Position a = points[v.a], b = points[v.b], l = points[v.l], r = points[v.r];
        if (ddt::orient(r, b, l) <= 0 || ddt::orient(l, a, r) <= 0) continue;  // not strictly convex
        Mesh broken = mesh;
        ddt::flipEdge(broken, e);
        CHECK(ddt::checkDelaunay(broken) != "");
        ++flipped;
    }
    CHECK(flipped == 20);
}

TEST_CASE("delaunay: inCircle is exact up to coordinates of 2^26", "[delaunay]") {
    std::mt19937_64 rng(13);
    auto checkAgainstReference = [](Position a, Position b, Position c, Position d) {
        const __int128 det = ddt::inCircleDeterminant(a, b, c, d);
        CHECK((det == referenceInCircle(a, b, c, d)));
        if (ddt::orient(a, b, c) > 0 && det != 0) CHECK(ddt::inCircle(a, b, c, d) == (det > 0));
    };
    const int32_t top = (1 << 26) - 1;
    std::uniform_int_distribution<int32_t> anywhere(0, top), near_top(top - (1 << 12), top), low(0, 1 << 12);
    for (int i = 0; i < 20000; ++i) {
        Position p[4];
        for (Position& q : p) {
            switch (i % 3) {
            case 0: q = {anywhere(rng), anywhere(rng)}; break;
            case 1: q = {near_top(rng), near_top(rng)}; break;
            default: q = {i % 2 ? low(rng) : top - low(rng), i % 4 < 2 ? low(rng) : top - low(rng)}; break;
            }
        }
        if (ddt::orient(p[0], p[1], p[2]) < 0) std::swap(p[1], p[2]);
        checkAgainstReference(p[0], p[1], p[2], p[3]);
    }
    // Exactly cocircular points across most of the range (radius 3 · 5^10 ≈ 1.75 · 2^24), and
    // each moved by one unit: determinant 0, then tiny values of either sign.
    const int32_t half = 1 << 25;
    const std::vector<Position> circle = circlePoints({half, half}, 10, 3);
    REQUIRE(circle.size() == 84);
    std::uniform_int_distribution<size_t> pick(0, circle.size() - 1);
    int zero = 0, positive = 0, negative = 0;
    for (int i = 0; i < 3000; ++i) {
        Position p[4] = {circle[pick(rng)], circle[pick(rng)], circle[pick(rng)], circle[pick(rng)]};
        if (p[0] == p[1] || p[0] == p[2] || p[0] == p[3] || p[1] == p[2] || p[1] == p[3] || p[2] == p[3]) continue;
        if (ddt::orient(p[0], p[1], p[2]) < 0) std::swap(p[1], p[2]);
        CHECK((ddt::inCircleDeterminant(p[0], p[1], p[2], p[3]) == 0));
        CHECK((referenceInCircle(p[0], p[1], p[2], p[3]) == 0));
        ++zero;
        for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
            const Position moved = {p[3].x + dx, p[3].y + dy};
            const __int128 det = ddt::inCircleDeterminant(p[0], p[1], p[2], moved);
            checkAgainstReference(p[0], p[1], p[2], moved);
            positive += det > 0;
            negative += det < 0;
        }
    }
    CHECK(zero > 2000);
    CHECK(positive > 1000);
    CHECK(negative > 1000);
}

TEST_CASE("delaunay: the symbolic tie-break is consistent", "[delaunay]") {
    // For four cocircular points in convex position, exactly one diagonal has both its
    // triangles empty, and the answer does not depend on which vertex the triangle starts at.
    std::mt19937_64 rng(17);
    const std::vector<Position> circle = circlePoints({1 << 24, 1 << 24}, 6, 5);
    std::uniform_int_distribution<size_t> pick(0, circle.size() - 1);
    int tested = 0;
    for (int i = 0; i < 2000; ++i) {
        std::vector<Position> q = {circle[pick(rng)], circle[pick(rng)], circle[pick(rng)], circle[pick(rng)]};
        std::sort(q.begin(), q.end(), [](Position p, Position r) { return p.y != r.y ? p.y < r.y : p.x < r.x; });
        if (std::adjacent_find(q.begin(), q.end()) != q.end()) continue;
        // Around the circle's centre, in positive order.
        const Position centre = {1 << 24, 1 << 24};
        std::sort(q.begin(), q.end(), [&](Position p, Position r) {
            const bool p_upper = p.y < centre.y || (p.y == centre.y && p.x > centre.x);
            const bool r_upper = r.y < centre.y || (r.y == centre.y && r.x > centre.x);
            if (p_upper != r_upper) return p_upper;
            return ddt::orient(centre, r, p) > 0;
        });
        if (ddt::orient(q[0], q[1], q[2]) < 0) std::reverse(q.begin(), q.end());
        REQUIRE(ddt::orient(q[0], q[1], q[2]) > 0);
        REQUIRE(ddt::orient(q[0], q[2], q[3]) > 0);
        const bool diagonal_02 = !ddt::inCircle(q[0], q[1], q[2], q[3]) && !ddt::inCircle(q[0], q[2], q[3], q[1]);
        const bool diagonal_13 = !ddt::inCircle(q[1], q[2], q[3], q[0]) && !ddt::inCircle(q[1], q[3], q[0], q[2]);
        CHECK(diagonal_02 != diagonal_13);
        CHECK(ddt::inCircle(q[0], q[1], q[2], q[3]) == ddt::inCircle(q[1], q[2], q[0], q[3]));
        CHECK(ddt::inCircle(q[0], q[1], q[2], q[3]) == ddt::inCircle(q[2], q[0], q[1], q[3]));
        // The highest-priority point never lies in the circle of the others.
        const Position top = *std::max_element(q.begin(), q.end(), [](Position p, Position r) { return ddt::outranks(r, p); });
        for (int k = 0; k < 4; ++k) {
            if (!(q[k] == top)) continue;
            CHECK_FALSE(ddt::inCircle(q[(k + 1) % 4], q[(k + 2) % 4], q[(k + 3) % 4], top));
        }
        ++tested;
    }
    CHECK(tested > 1000);
}

TEST_CASE("delaunay: delaunayInputProblem names what is missing", "[delaunay]") {
    CHECK(ddt::delaunayInputProblem({}) == "fewer than 3 points");
    CHECK(ddt::delaunayInputProblem({pixel(1, 1)}) == "fewer than 3 points");
    CHECK(ddt::delaunayInputProblem({pixel(1, 1), pixel(2, 3)}) == "fewer than 3 points");
    CHECK(ddt::delaunayInputProblem({pixel(0, 0), pixel(1, 1), pixel(3, 3), pixel(7, 7)}) == "all points are collinear");
    CHECK(ddt::delaunayInputProblem({pixel(0, 5), pixel(1, 5), pixel(2, 5)}) == "all points are collinear");
    CHECK(ddt::delaunayInputProblem({pixel(0, 0), pixel(1, 0), pixel(0, 1), pixel(1, 0)}) ==
          "two points at the same place");
    CHECK(ddt::delaunayInputProblem({pixel(0, 0), pixel(0, 0), pixel(0, 0)}) == "two points at the same place");
    CHECK(ddt::delaunayInputProblem({pixel(0, 0), pixel(1, 0), pixel(0, 1)}) == "");
    CHECK(ddt::delaunayInputProblem({pixel(0, 0), pixel(1, 0), pixel(2, 0), pixel(3, 1)}) == "");
    CHECK(ddt::delaunayInputProblem({{-1, 0}, pixel(1, 0), pixel(0, 1)}) != "");
}
