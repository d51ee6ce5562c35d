#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <functional>
#include <random>
#include <set>

#include "mesh.h"
#include "test_support.h"

using ddt::kNone;
using ddt::test::edgeBetween;
using ddt::test::triangulationProblem;

namespace {

// The 3×3 grid, vertex ids in the corners, edge ids on the edges (right, down, diagonal per
// vertex in row-major order; the last column has only "down", the last row only "right"):
//
//     0 ---0--- 1 ---3--- 2
//     | \       | \       |
//     1   2     4   5     6
//     |     \   |     \   |
//     3 ---7--- 4 --10--- 5
//     | \       | \       |
//     8   9    11  12    13
//     |     \   |     \   |
//     6 --14--- 7 --15--- 8
struct Record {
    uint32_t a, b, l, r, bl, la, ar, rb;
};

Record recordOf(const ddt::Mesh& mesh, uint32_t e) {
    const ddt::EdgeVertices& v = mesh.vertices[e];
    const ddt::EdgeNeighbours& n = mesh.neighbours[e];
    return {v.a, v.b, v.l, v.r, n.bl, n.la, n.ar, n.rb};
}

bool operator==(const Record& x, const Record& y) {
    return x.a == y.a && x.b == y.b && x.l == y.l && x.r == y.r && x.bl == y.bl && x.la == y.la && x.ar == y.ar &&
           x.rb == y.rb;
}

std::ostream& operator<<(std::ostream& out, const Record& x) {
    auto id = [](uint32_t i) { return i == kNone ? std::string("-") : std::to_string(i); };
    return out << "{" << id(x.a) << "," << id(x.b) << "," << id(x.l) << "," << id(x.r) << " | " << id(x.bl) << ","
               << id(x.la) << "," << id(x.ar) << "," << id(x.rb) << "}";
}

}  // namespace

TEST_CASE("mesh: the grid triangulation is valid") {
    for (auto [w, h] : {std::pair{2u, 2u}, {3u, 2u}, {2u, 5u}, {7u, 4u}, {16u, 9u}}) {
        ddt::Mesh mesh = ddt::buildGridMesh(w, h);
        CHECK(ddt::checkMesh(mesh) == "");
        CHECK(triangulationProblem(mesh) == "");
    }
}

TEST_CASE("mesh: edge ids follow right, down, diagonal per vertex in row-major order") {
    ddt::Mesh mesh = ddt::buildGridMesh(3, 3);
    REQUIRE(mesh.edgeCount() == 16);
    // (id, lower endpoint, higher endpoint), read off the picture above.
    const uint32_t expected[16][3] = {{0, 0, 1},  {1, 0, 3},  {2, 0, 4},  {3, 1, 2},  {4, 1, 4},   {5, 1, 5},
                                      {6, 2, 5},  {7, 3, 4},  {8, 3, 6},  {9, 3, 7},  {10, 4, 5},  {11, 4, 7},
                                      {12, 4, 8}, {13, 5, 8}, {14, 6, 7}, {15, 7, 8}};
    for (const auto& row : expected) {
        INFO("edge " << row[0]);
        CHECK(mesh.vertices[row[0]].a == row[1]);
        CHECK(mesh.vertices[row[0]].b == row[2]);
    }
}

TEST_CASE("mesh: grid records hold the adjacent vertices and neighbours by hand") {
    ddt::Mesh mesh = ddt::buildGridMesh(3, 3);
    // Left triangle (a, b, l) and right triangle (b, a, r) are positive: clockwise on screen.
    // Neighbours in bl, la, ar, rb order; "-" is kNone.
    CHECK(recordOf(mesh, 0) == Record{0, 1, 4, kNone, 4, 2, kNone, kNone});  // top hull edge
    CHECK(recordOf(mesh, 1) == Record{0, 3, kNone, 4, kNone, kNone, 2, 7});  // left hull edge
    CHECK(recordOf(mesh, 2) == Record{0, 4, 3, 1, 7, 1, 0, 4});              // diagonal of cell (0,0)
    CHECK(recordOf(mesh, 7) == Record{3, 4, 7, 0, 11, 9, 1, 2});             // interior horizontal
    CHECK(recordOf(mesh, 11) == Record{4, 7, 3, 8, 9, 7, 12, 15});           // interior vertical
    CHECK(recordOf(mesh, 12) == Record{4, 8, 7, 5, 15, 11, 10, 13});         // diagonal of cell (1,1)
    CHECK(recordOf(mesh, 13) == Record{5, 8, 4, kNone, 12, 10, kNone, kNone});  // right hull edge
    CHECK(recordOf(mesh, 15) == Record{7, 8, kNone, 4, kNone, kNone, 11, 12});  // bottom hull edge
}

TEST_CASE("mesh: gridEdgeCount counts horizontal, vertical and diagonal edges") {
    // (w−1)·h horizontal + w·(h−1) vertical + (w−1)·(h−1) diagonal.
    CHECK(ddt::gridEdgeCount(2, 2) == 5);
    CHECK(ddt::gridEdgeCount(3, 3) == 16);
    CHECK(ddt::gridEdgeCount(4, 3) == 23);
    CHECK(ddt::gridEdgeCount(2, 7) == 7 + 12 + 6);
    // 65536² needs 64 bits: 2·65535·65536 + 65535² = 12884639745 ≈ 1.3e10 > 2^32.
    CHECK(ddt::gridEdgeCount(65536, 65536) == 12884639745ull);
    for (auto [w, h] : {std::pair{2u, 2u}, {5u, 3u}, {3u, 8u}, {17u, 11u}})
        CHECK(ddt::buildGridMesh(w, h).edgeCount() == ddt::gridEdgeCount(w, h));
}

TEST_CASE("mesh: a flip rotates the record and patches the four neighbours") {
    ddt::Mesh mesh = ddt::buildGridMesh(3, 3);
    REQUIRE(ddt::flipIsConvex(ddt::flipStencil(mesh, 2), ddt::placesOf(mesh)));
    ddt::flipEdge(mesh, 2);
    // Cell (0,0) now has the diagonal 1–3:
    //     0 ------- 1
    //     |       / |
    //     |     /   |
    //     |   /     |
    //     3 ------- 4
    CHECK(recordOf(mesh, 2) == Record{1, 3, 0, 4, 1, 0, 4, 7});  // (r, l, a, b), (la, ar, rb, bl)
    CHECK(recordOf(mesh, 0) == Record{0, 1, 3, kNone, 2, 1, kNone, kNone});
    CHECK(recordOf(mesh, 1) == Record{0, 3, kNone, 1, kNone, kNone, 0, 2});
    CHECK(recordOf(mesh, 4) == Record{1, 4, 3, 5, 7, 2, 5, 10});
    CHECK(recordOf(mesh, 7) == Record{3, 4, 7, 1, 11, 9, 2, 4});
    CHECK(ddt::checkMesh(mesh) == "");
    CHECK(triangulationProblem(mesh) == "");
}

TEST_CASE("mesh: flipping an edge twice restores the mesh, four times the record") {
    // A flip rotates the record a quarter turn ((a, b, l, r) -> (r, l, a, b)), so two flips give
    // back the same edge a–b stored reversed, (b, a, r, l), with every neighbour record exactly as
    // before; four flips restore e's record too.
    std::mt19937 rng(7);
    ddt::Mesh mesh = ddt::buildGridMesh(6, 5);
    ddt::test::flipRandomEdges(mesh, rng, 40);
    REQUIRE(ddt::checkMesh(mesh) == "");
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
        if (!ddt::flipIsConvex(ddt::flipStencil(mesh, e), ddt::placesOf(mesh))) continue;
        INFO("edge " << e);
        const ddt::Mesh before = mesh;
        const Record r = recordOf(mesh, e);
        ddt::flipEdge(mesh, e);
        REQUIRE(ddt::flipIsConvex(ddt::flipStencil(mesh, e), ddt::placesOf(mesh)));  // a convex quad stays convex
        ddt::flipEdge(mesh, e);
        CHECK(recordOf(mesh, e) == Record{r.b, r.a, r.r, r.l, r.ar, r.rb, r.bl, r.la});
        ddt::Mesh expected = before;
        expected.vertices[e] = mesh.vertices[e];
        expected.neighbours[e] = mesh.neighbours[e];
        CHECK(ddt::test::sameRecords(mesh, expected));
        ddt::flipEdge(mesh, e);
        ddt::flipEdge(mesh, e);
        CHECK(ddt::test::sameRecords(mesh, before));
    }
}

TEST_CASE("mesh: random convex flips keep the mesh valid") {
    std::mt19937 rng(20240611);
    for (auto [w, h] : {std::pair{2u, 2u}, {3u, 2u}, {2u, 6u}, {5u, 5u}, {9u, 4u}, {12u, 10u}}) {
        ddt::Mesh mesh = ddt::buildGridMesh(w, h);
        for (int round = 0; round < 30; ++round) {
            ddt::test::flipRandomEdges(mesh, rng, 5);
            INFO(w << "x" << h << " round " << round);
            REQUIRE(ddt::checkMesh(mesh) == "");
            REQUIRE(triangulationProblem(mesh) == "");
            REQUIRE(ddt::listTriangles(mesh).size() == 2 * size_t(w - 1) * (h - 1));
        }
    }
}

TEST_CASE("mesh: flipIsConvex agrees with an independent convexity test") {
    std::mt19937 rng(99);
    ddt::Mesh mesh = ddt::buildGridMesh(8, 7);
    size_t convex = 0, not_convex = 0;
    for (int round = 0; round < 20; ++round) {
        ddt::test::flipRandomEdges(mesh, rng, 10);
        for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
            const bool mine = ddt::test::quadIsStrictlyConvex(mesh, e);
            CHECK(ddt::flipIsConvex(ddt::flipStencil(mesh, e), ddt::placesOf(mesh)) == mine);
            (mine ? convex : not_convex)++;
        }
    }
    CHECK(convex > 0);
    CHECK(not_convex > 0);
}

TEST_CASE("mesh: flipStencil reads the quadrilateral and the far vertices") {
    ddt::Mesh mesh = ddt::buildGridMesh(3, 3);
    // Edge 12 = 4–8 with l = 7, r = 5; its neighbours 8–7, 7–4, 4–5, 5–8 have the far vertices
    // kNone (bottom hull), 3, 1 and kNone (right hull).
    ddt::FlipStencil s = ddt::flipStencil(mesh, 12);
    CHECK(s.a == 4);
    CHECK(s.b == 8);
    CHECK(s.l == 7);
    CHECK(s.r == 5);
    CHECK(s.far_bl == kNone);
    CHECK(s.far_la == 3);
    CHECK(s.far_ar == 1);
    CHECK(s.far_rb == kNone);
    // Edge 2 = 0–4, l = 3, r = 1: neighbours 4–3, 3–0, 0–1, 1–4 have far vertices 7, -, -, 5.
    s = ddt::flipStencil(mesh, 2);
    CHECK(s.far_bl == 7);
    CHECK(s.far_la == kNone);
    CHECK(s.far_ar == kNone);
    CHECK(s.far_rb == 5);
}

TEST_CASE("mesh: checkMesh catches every kind of corruption") {
    // 4×4 grid; e is the diagonal 5–10 of cell (1,1), an interior edge well inside.
    const ddt::Mesh good = ddt::buildGridMesh(4, 4);
    const uint32_t e = edgeBetween(good, 5, 10);
    REQUIRE(e != kNone);
    REQUIRE(ddt::checkMesh(good) == "");
    const ddt::EdgeVertices ev = good.vertices[e];
    const ddt::EdgeNeighbours en = good.neighbours[e];
    REQUIRE(ev.l == 9);   // triangle (5, 10, 9)
    REQUIRE(ev.r == 6);   // triangle (10, 5, 6)
    const uint32_t hull_edge = edgeBetween(good, 0, 1);

    struct Corruption {
        const char* name;
        std::function<void(ddt::Mesh&)> apply;
    };
    const Corruption corruptions[] = {
        {"broken symmetric link (neighbour forgets e)",
         [&](ddt::Mesh& m) {
             ddt::EdgeNeighbours& n = m.neighbours[en.bl];
             for (uint32_t* slot : {&n.bl, &n.la, &n.ar, &n.rb})
                 if (*slot == e) *slot = en.la;
         }},
        {"neighbour slots of e swapped", [&](ddt::Mesh& m) { std::swap(m.neighbours[e].bl, m.neighbours[e].la); }},
        {"wrong adjacent vertex, still a positive triangle", [&](ddt::Mesh& m) { m.vertices[e].l = 13; }},
        {"adjacent vertex on the wrong side", [&](ddt::Mesh& m) { m.vertices[e].l = 6; }},
        {"adjacent vertex out of range", [&](ddt::Mesh& m) { m.vertices[e].r = 16; }},
        {"main vertex out of range", [&](ddt::Mesh& m) { m.vertices[e].b = 99; }},
        {"main vertices equal", [&](ddt::Mesh& m) { m.vertices[e].b = m.vertices[e].a; }},
        {"duplicate edge (a record copied over another)",
         [&](ddt::Mesh& m) {
             const uint32_t other = edgeBetween(m, 0, 5);
             m.vertices[other] = m.vertices[e];
             m.neighbours[other] = m.neighbours[e];
         }},
        {"neighbour id out of range", [&](ddt::Mesh& m) { m.neighbours[e].ar = m.edgeCount(); }},
        {"interior edge with one triangle",
         [&](ddt::Mesh& m) {
             m.vertices[e].r = kNone;
             m.neighbours[e].ar = m.neighbours[e].rb = kNone;
         }},
        {"edge without triangles",
         [&](ddt::Mesh& m) {
             m.vertices[hull_edge].l = kNone;
             m.neighbours[hull_edge] = {kNone, kNone, kNone, kNone};
         }},
        {"hull edge with links on its empty side", [&](ddt::Mesh& m) { m.neighbours[hull_edge].ar = e; }},
        {"an edge missing", [&](ddt::Mesh& m) {
             m.vertices.pop_back();
             m.neighbours.pop_back();
         }},
        {"neighbour array shorter", [&](ddt::Mesh& m) { m.neighbours.pop_back(); }},
        {"forced flip across a degenerate quadrilateral",
         [&](ddt::Mesh& m) {
             // Flip e (5–10 -> 6–9); then 5–6 has the quad 5, 1, 6, 9 with 1, 5, 9 collinear,
             // so its forced flip to 1–9 leaves the flat triangle (9, 5, 1).
             ddt::flipEdge(m, e);
             const uint32_t f = edgeBetween(m, 5, 6);
             REQUIRE_FALSE(ddt::flipIsConvex(ddt::flipStencil(m, f), ddt::placesOf(m)));
             ddt::flipEdge(m, f);
         }},
    };
    for (const Corruption& c : corruptions) {
        ddt::Mesh mesh = good;
        c.apply(mesh);
        INFO(c.name);
        const std::string problem = ddt::checkMesh(mesh);
        CHECK(problem != "");
        CHECK(triangulationProblem(mesh) != "");
        UNSCOPED_INFO(c.name << ": " << problem);
    }
}

TEST_CASE("mesh: checkMesh catches explicit positions that break the triangulation") {
    // A moved mesh (test_support.h) is valid; each corruption moves one vertex. On the 4×4
    // grid, vertex 5 = (1, 1) is interior, 1 = (1, 0) on the top side, 0 a corner.
    std::mt19937 rng(3);
    REQUIRE(ddt::checkMesh(ddt::test::movedMesh(6, 5, rng)) == "");
    ddt::Mesh good = ddt::buildGridMesh(4, 4);
    ddt::makePositionsExplicit(good);
    REQUIRE(ddt::checkMesh(good) == "");
    const int32_t one = ddt::kPositionOne;
    struct Corruption {
        const char* name;
        uint32_t vertex;
        ddt::Position to;
    };
    const Corruption corruptions[] = {
        {"interior vertex across its neighbours", 5, {3 * one, one}},
        {"interior vertex onto another", 5, {2 * one, 2 * one}},
        {"interior vertex onto an edge (a flat triangle)", 5, {one, 2 * one}},
        {"border vertex off its side, inwards", 1, {one, one / 2}},
        {"border vertex off its side, outwards", 1, {one, -one / 2}},
        {"corner moved along a side", 0, {one / 2, 0}},
    };
    for (const Corruption& c : corruptions) {
        ddt::Mesh mesh = good;
        mesh.positions[c.vertex] = c.to;
        INFO(c.name);
        const std::string problem = ddt::checkMesh(mesh);
        CHECK(problem != "");
        UNSCOPED_INFO(c.name << ": " << problem);
    }
    ddt::Mesh short_positions = good;
    short_positions.positions.pop_back();
    CHECK(ddt::checkMesh(short_positions) == "wrong number of positions");
}

TEST_CASE("mesh: orientationSign is exact at the extremes of the fixed-point range") {
    // Coordinates near 2^30 (the largest positioned side): the products reach 2^60, where a
    // double's 53 bits would round. Checked against 128-bit integer arithmetic written here.
    ddt::Mesh mesh;
    mesh.width = mesh.height = ddt::kMaxPositionedSide;
    const int32_t top = int32_t(ddt::kMaxPositionedSide) * ddt::kPositionOne - 1;
    std::mt19937 rng(11);
    std::uniform_int_distribution<int32_t> half(0, top / 2), quarter(0, top / 4), nudge(-1, 1);
    mesh.positions.resize(3);
    int signs[3] = {};
    for (int i = 0; i < 20000; ++i) {
        // r near the middle of p–q (on it without the nudge), where rounding bites.
        const ddt::Position p{half(rng), half(rng)}, d{quarter(rng), quarter(rng)};
        const ddt::Position q{p.x + 2 * d.x, p.y + 2 * d.y}, r{p.x + d.x + nudge(rng), p.y + d.y + nudge(rng)};
        mesh.positions = {p, q, r};
        const __int128 exact = __int128(q.x - p.x) * (r.y - p.y) - __int128(q.y - p.y) * (r.x - p.x);
        const int expected = (exact > 0) - (exact < 0);
        REQUIRE(ddt::orientationSign(mesh, 0, 1, 2) == expected);
        ++signs[expected + 1];
    }
    CHECK(signs[0] > 0);  // every sign occurred: the test met the boundary cases
    CHECK(signs[1] > 0);
    CHECK(signs[2] > 0);
}

TEST_CASE("mesh: the ROI of an interior grid edge is its 12-edge 2-region (paper Fig. 4a)") {
    ddt::Mesh mesh = ddt::buildGridMesh(7, 7);
    auto v = [&](int x, int y) { return uint32_t(y * 7 + x); };
    auto ids = [&](std::vector<std::pair<uint32_t, uint32_t>> pairs) {
        std::vector<uint32_t> out;
        for (auto [p, q] : pairs) {
            uint32_t id = edgeBetween(mesh, p, q);
            REQUIRE(id != kNone);
            out.push_back(id);
        }
        std::sort(out.begin(), out.end());
        return out;
    };
    // The diagonal e = (3,3)–(4,4). Its 1-region is the cell's four sides; the far triangle of
    // each side adds its two other edges (2-region: 4 + 8 = 12 edges, e excluded):
    //
    //          x=2    x=3    x=4    x=5
    //    y=2          o
    //                 | `.
    //                 |   `.
    //    y=3   o------o------o
    //            `.   | `.   | `.
    //              `. |  e `.|   `.
    //    y=4          o------o------o
    //                   `.   |
    //                     `. |
    //    y=5                 o
    const uint32_t e = edgeBetween(mesh, v(3, 3), v(4, 4));
    const std::vector<uint32_t> ring1 = ids({{v(3, 3), v(4, 3)}, {v(4, 3), v(4, 4)}, {v(3, 4), v(4, 4)}, {v(3, 3), v(3, 4)}});
    std::vector<uint32_t> ring2 = ids({{v(3, 2), v(4, 3)},
                                       {v(3, 2), v(3, 3)},
                                       {v(4, 3), v(5, 4)},
                                       {v(4, 4), v(5, 4)},
                                       {v(4, 4), v(4, 5)},
                                       {v(3, 4), v(4, 5)},
                                       {v(2, 3), v(3, 3)},
                                       {v(2, 3), v(3, 4)}});
    std::vector<uint32_t> region2 = ring1;
    region2.insert(region2.end(), ring2.begin(), ring2.end());
    std::sort(region2.begin(), region2.end());
    CHECK(ddt::regionOf(mesh, e, 1) == ring1);
    CHECK(ddt::regionOf(mesh, e, 2) == region2);
    CHECK(region2.size() == 12);

    // Every interior edge kind (right, down, diagonal) far from the hull has a 12-edge ROI, and a
    // 26-edge 3-region: the 8 edges added by degree 2 are the outer sides of 4 triangles around
    // the quad; each has one more triangle beyond it (8 triangles, 16 sides), and exactly two
    // sides are shared by two of those triangles (for the diagonal (3,3)–(4,4): (2,2)–(3,3) and
    // (4,4)–(5,5)), so degree 3 adds 16 − 2 = 14 edges: 12 + 14 = 26 (paper Fig. 4b).
    for (auto [p, q] : {std::pair{v(3, 3), v(4, 4)}, {v(3, 3), v(4, 3)}, {v(3, 3), v(3, 4)}}) {
        const uint32_t f = edgeBetween(mesh, p, q);
        INFO("edge " << p << "-" << q);
        CHECK(ddt::regionOf(mesh, f, 1).size() == 4);
        CHECK(ddt::regionOf(mesh, f, 2).size() == 12);
        CHECK(ddt::regionOf(mesh, f, 3).size() == 26);
    }
    // The two shared far sides of the diagonal's 3-region are in it.
    const std::vector<uint32_t> region3 = ddt::regionOf(mesh, e, 3);
    CHECK(std::binary_search(region3.begin(), region3.end(), edgeBetween(mesh, v(2, 2), v(3, 3))));
    CHECK(std::binary_search(region3.begin(), region3.end(), edgeBetween(mesh, v(4, 4), v(5, 5))));
    CHECK_FALSE(std::binary_search(region3.begin(), region3.end(), e));

    // On the 2×2 grid the diagonal's region is just the four hull edges at any degree.
    ddt::Mesh tiny = ddt::buildGridMesh(2, 2);
    CHECK(ddt::regionOf(tiny, 2, 2) == std::vector<uint32_t>{0, 1, 3, 4});
}

TEST_CASE("mesh: listTriangles gives 2(w-1)(h-1) positive triangles, each once") {
    ddt::Mesh tiny = ddt::buildGridMesh(2, 2);
    // 0 --- 1      triangles (0, 1, 3) and (0, 3, 2), clockwise on screen
    // |  \  |
    // 2 --- 3
    std::vector<ddt::Triangle> t = ddt::listTriangles(tiny);
    REQUIRE(t.size() == 2);
    std::set<std::array<uint32_t, 3>> got;
    for (const ddt::Triangle& x : t) {
        // Rotate so the smallest id comes first (orientation kept).
        std::array<uint32_t, 3> a{x.v0, x.v1, x.v2};
        std::rotate(a.begin(), std::min_element(a.begin(), a.end()), a.end());
        got.insert(a);
    }
    CHECK(got == std::set<std::array<uint32_t, 3>>{{0, 1, 3}, {0, 3, 2}});

    std::mt19937 rng(5);
    for (auto [w, h] : {std::pair{2u, 3u}, {5u, 4u}, {11u, 7u}}) {
        ddt::Mesh mesh = ddt::buildGridMesh(w, h);
        ddt::test::flipRandomEdges(mesh, rng, 3 * w * h);
        std::vector<ddt::Triangle> triangles = ddt::listTriangles(mesh);
        CHECK(triangles.size() == 2 * size_t(w - 1) * (h - 1));
        std::set<std::array<uint32_t, 3>> distinct;
        int64_t twice_area = 0;
        for (const ddt::Triangle& x : triangles) {
            const int64_t area = ddt::test::twiceArea(mesh, x.v0, x.v1, x.v2);
            CHECK(area > 0);
            twice_area += area;
            std::array<uint32_t, 3> a{x.v0, x.v1, x.v2};
            std::sort(a.begin(), a.end());
            distinct.insert(a);
        }
        CHECK(distinct.size() == triangles.size());
        CHECK(twice_area == 2 * int64_t(w - 1) * (h - 1));
    }
}

TEST_CASE("mesh: built from its own triangles, a mesh has the same triangles") {
    std::mt19937 rng(21);
    ddt::Mesh mesh = ddt::buildGridMesh(7, 5);
    ddt::test::flipRandomEdges(mesh, rng, 40);
    std::vector<uint32_t> ids;
    for (const ddt::Triangle& t : ddt::listTriangles(mesh)) ids.insert(ids.end(), {t.v0, t.v1, t.v2});
    const ddt::Mesh rebuilt = ddt::meshFromTriangles(7, 5, ids);
    CHECK(ddt::checkMesh(rebuilt) == "");
    CHECK(rebuilt.edgeCount() == mesh.edgeCount());
    std::vector<std::array<uint32_t, 3>> before, after;
    auto canonical = [](const ddt::Triangle& t) {
        std::array<uint32_t, 3> v{t.v0, t.v1, t.v2};
        std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
        return v;
    };
    for (const ddt::Triangle& t : ddt::listTriangles(mesh)) before.push_back(canonical(t));
    for (const ddt::Triangle& t : ddt::listTriangles(rebuilt)) after.push_back(canonical(t));
    std::sort(before.begin(), before.end());
    std::sort(after.begin(), after.end());
    CHECK(before == after);
}
