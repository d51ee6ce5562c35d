// core/delaunay/sweep_triangulation.h and canonical_edges.h: the device Delaunay's CPU steps.
#include <catch2/catch.hpp>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "canonical_edges.h"
#include "delaunay.h"
#include "mesh.h"
#include "sweep_triangulation.h"
#include "test_support.h"

using namespace ddt;

namespace {

std::vector<Position> rowMajor(std::vector<Position> points) {
    std::sort(points.begin(), points.end(), [](Position p, Position q) { return p.y != q.y ? p.y < q.y : p.x < q.x; });
    points.erase(std::unique(points.begin(), points.end()), points.end());
    return points;
}

}  // namespace

TEST_CASE("sweep triangulation: a triangle is one triangle", "[delaunay]") {
    //  0 ---- 1        row-major: 0 = (0, 0), 1 = (4, 0), 2 = (1, 3)
    //   \    /
    //    \  /
    //     2
    const std::vector<Position> points = {{0, 0}, {4096, 0}, {1024, 3072}};
    const Mesh mesh = sweepTriangulation(5, 4, points);
    REQUIRE(mesh.edgeCount() == 3);
    CHECK(checkMesh(mesh, MeshHull::convex) == "");
    CHECK(mesh.positions == points);
}

TEST_CASE("sweep triangulation: valid on random, gridded and collinear point sets", "[delaunay]") {
    std::mt19937 rng(21);
    std::vector<std::vector<Position>> sets;
    for (const uint32_t count : {3u, 4u, 10u, 1000u, 20000u}) {
        std::uniform_int_distribution<int32_t> coordinate(0, 99 * kPositionOne);
        std::vector<Position> points(count);
        for (Position& p : points) p = {coordinate(rng), coordinate(rng)};
        sets.push_back(rowMajor(points));
    }
    std::vector<Position> grid;
    for (int32_t y = 0; y < 100; ++y)
        for (int32_t x = 0; x < 100; ++x) grid.push_back({x * kPositionOne, y * kPositionOne});
    sets.push_back(grid);
    std::vector<Position> lines;  // collinear first points, and a hull side of many points
    for (int32_t x = 0; x < 100; ++x) {
        lines.push_back({x * kPositionOne, 0});
        lines.push_back({x * kPositionOne, x * 512 + 1024});
    }
    sets.push_back(rowMajor(lines));
    // Few distinct x's and y's: many points above one another (vertical front and hull edges,
    // points right above L or R) and rows of several points.
    for (int set = 0; set < 300; ++set) {
        std::uniform_int_distribution<int32_t> coordinate(0, int32_t(1 + set % 12) * kPositionOne);
        std::vector<Position> points(3 + set % 60);
        for (Position& p : points) p = {coordinate(rng), coordinate(rng)};
        points = rowMajor(points);
        if (points.size() >= 3 && delaunayInputProblem(points).empty()) sets.push_back(points);
    }
    for (const std::vector<Position>& points : sets) {
        INFO(points.size() << " points");
        REQUIRE(delaunayInputProblem(points) == "");
        const Mesh mesh = sweepTriangulation(100, 100, points);
        CHECK(checkMesh(mesh, MeshHull::convex) == "");
        // Every point is a vertex: a triangulation of n points with h on the hull has 3n − 3 − h
        // edges, so as many as the Delaunay triangulation of the same points.
        CHECK(mesh.edgeCount() == delaunayOfPoints(100, 100, points).edgeCount());
    }
}

TEST_CASE("sweep triangulation: two rows of a grid are zipped with the grid's diagonals", "[delaunay]") {
    // 0 --- 1 --- 2        the first row and the second, zipped cell by cell: each unit
    //   \     \     \       cell cut by (x, y)–(x + 1, y + 1), as buildGridMesh (and the
    // 3 --- 4 --- 5        Delaunay tie-break) cuts it
    for (const uint32_t width : {2u, 3u, 40u}) {
        INFO(width << " x 2");
        std::vector<Position> points;
        for (uint32_t v = 0; v < 2 * width; ++v) points.push_back(gridPosition(v, width));
        Mesh mesh = sweepTriangulation(width, 2, points);
        renumberCanonically(mesh);
        Mesh grid = buildGridMesh(width, 2);
        makePositionsExplicit(grid);
        CHECK(test::sameRecords(mesh, grid));
    }
}

TEST_CASE("canonical edges: any numbering of a mesh renumbers to the reference's", "[delaunay]") {
    std::mt19937 rng(22);
    std::uniform_int_distribution<int32_t> coordinate(0, 199 * kPositionOne);
    std::vector<Position> points(3000);
    for (Position& p : points) p = {coordinate(rng), coordinate(rng)};
    points = rowMajor(points);
    const Mesh reference = delaunayOfPoints(200, 200, points);
    // Shuffle the ids and turn every other edge end for end.
    const uint32_t edges = reference.edgeCount();
    std::vector<uint32_t> new_id(edges);
    std::iota(new_id.begin(), new_id.end(), 0u);
    std::shuffle(new_id.begin(), new_id.end(), rng);
    Mesh shuffled = reference;
    auto renamed = [&](uint32_t e) { return e == kNone ? kNone : new_id[e]; };
    for (uint32_t e = 0; e < edges; ++e) {
        EdgeVertices v = reference.vertices[e];
        const EdgeNeighbours& m = reference.neighbours[e];
        EdgeNeighbours n = {renamed(m.bl), renamed(m.la), renamed(m.ar), renamed(m.rb)};
        if (e % 2) {
            v = {v.b, v.a, v.r, v.l};
            n = {n.ar, n.rb, n.bl, n.la};
        }
        shuffled.vertices[new_id[e]] = v;
        shuffled.neighbours[new_id[e]] = n;
    }
    REQUIRE(checkMesh(shuffled, MeshHull::convex) == "");
    REQUIRE_FALSE(test::sameRecords(shuffled, reference));
    renumberCanonically(shuffled);
    CHECK(test::sameRecords(shuffled, reference));
}
