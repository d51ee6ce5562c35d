// Edge collapses (core/simplify/edge_collapse.h): legal ones keep a valid mesh of the whole
// rectangle, illegal ones are refused, and compaction keeps it valid.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include "edge_collapse.h"
#include "greedy_simplify.h"
#include "test_support.h"

using namespace ddt;
using namespace ddt::test;

namespace {

Mesh compactCopy(Mesh mesh) {
    compactEdges(mesh);
    return mesh;
}

// Whether the walks around every vertex (forEachEdgeAt) give exactly the edges that name it,
// each once: what a scan of all edge records says.
bool walksMatchRecords(const Mesh& mesh, const VertexEdges& edges) {
    std::vector<std::vector<uint32_t>> scanned(mesh.vertexCount());
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e)
        if (!removedEdge(mesh, e)) {
            scanned[mesh.vertices[e].a].push_back(e);
            scanned[mesh.vertices[e].b].push_back(e);
        }
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        std::vector<uint32_t> walked;
        forEachEdgeAt(mesh, edges, v, [&](uint32_t f) { walked.push_back(f); });
        std::sort(walked.begin(), walked.end());
        if (walked != scanned[v]) return false;
    }
    return true;
}

}  // namespace

TEST_CASE("edge collapse: an interior vertex goes into its neighbour") {
    // The 4 × 4 grid; vertex 5 = (1, 1) collapses into 6 = (2, 1) along the right edge 5–6.
    //   0 - 1 - 2 - 3
    //   | \ | \ | \ |
    //   4 - 5 - 6 - 7
    //   | \ | \ | \ |
    //   8 - 9 -10 -11
    Mesh mesh = buildGridMesh(4, 4);
    VertexEdges edges(mesh);
    const uint32_t e = edgeBetween(mesh, 5, 6);
    const Collapse collapse{e, mesh.vertices[e].a == 6};
    REQUIRE(collapse.from(mesh) == 5);
    REQUIRE(canCollapse(mesh, edges, collapse));
    collapseEdge(mesh, edges, collapse);
    const Mesh compact = compactCopy(mesh);
    CHECK(checkMesh(compact) == "");
    CHECK(usedVertexCount(compact) == 15);
    CHECK(compact.edgeCount() == gridEdgeCount(4, 4) - 3);
    for (const EdgeVertices& v : compact.vertices) CHECK((v.a != 5 && v.b != 5 && v.l != 5 && v.r != 5));
    CHECK(edges.first[5] == kNone);
}

TEST_CASE("edge collapse: corners stay, border vertices move only along their side") {
    Mesh mesh = buildGridMesh(4, 4);
    VertexEdges edges(mesh);
    auto collapseOf = [&](uint32_t from, uint32_t to) {
        const uint32_t e = edgeBetween(mesh, from, to);
        REQUIRE(e != kNone);
        return Collapse{e, mesh.vertices[e].b == from};
    };
    CHECK_FALSE(canCollapse(mesh, edges, collapseOf(0, 1)));  // a corner
    CHECK_FALSE(canCollapse(mesh, edges, collapseOf(1, 5)));  // off the top side
    CHECK(canCollapse(mesh, edges, collapseOf(1, 2)));        // along it
    CHECK(canCollapse(mesh, edges, collapseOf(5, 1)));        // an interior vertex onto the side
}

TEST_CASE("edge collapse: random legal collapses keep a valid mesh down to the corners") {
    std::mt19937 rng(42);
    for (int trial = 0; trial < 6; ++trial) {
        const uint32_t w = 5 + trial, h = 4 + trial % 3;
        Mesh mesh = buildGridMesh(w, h);
        flipRandomEdges(mesh, rng, w * h);
        VertexEdges edges(mesh);
        uint32_t collapses = 0, refused = 0;
        for (int attempt = 0; attempt < 4000; ++attempt) {
            const uint32_t e = std::uniform_int_distribution<uint32_t>(0, mesh.edgeCount() - 1)(rng);
            if (removedEdge(mesh, e)) continue;
            const Collapse collapse{e, bool(rng() & 1)};
            if (!canCollapse(mesh, edges, collapse)) {
                ++refused;
                continue;
            }
            collapseEdge(mesh, edges, collapse);
            ++collapses;
            const Mesh compact = compactCopy(mesh);
            INFO("trial " << trial << ", collapse " << collapses);
            REQUIRE(checkMesh(compact) == "");
            REQUIRE(usedVertexCount(compact) == w * h - collapses);
            REQUIRE(walksMatchRecords(mesh, edges));
        }
        // Legal collapses run out only at the corners' two triangles.
        CHECK(usedVertexCount(mesh) == 4);
        CHECK(refused > 0);
    }
}

TEST_CASE("edge collapse: no collapse leaves a vertex more than kMaxCollapseValence edges") {
    // Every neighbour of the centre of a 24 × 24 grid collapsed into it while legal: the fan
    // would reach the 92 border vertices, the bound stops it.
    const uint32_t side = 24, centre = side / 2 * side + side / 2;
    const Mesh mesh = centreFanMesh(side);
    const VertexEdges edges(mesh);
    uint32_t valence = 0;
    forEachEdgeAt(mesh, edges, centre, [&](uint32_t) { ++valence; });
    INFO("the centre's edges: " << valence);
    CHECK(valence <= kMaxCollapseValence);
    // A collapse adds a few edges at a time: the fan ends just below the bound.
    CHECK(valence + 4 > kMaxCollapseValence);
    CHECK(checkMesh(compactCopy(mesh)) == "");
}
