// Half-edge collapses on the edge-centric mesh (core/mesh.h), the step of simplification.
//
// Collapsing vertex `from` into its neighbour `to` along edge e = (a, b) removes `from`, e, the
// triangles (a, b, l) and (b, a, r) and, of each, the edge from–l (from–r), whose outer side
// the edge to–l (to–r) takes over. `to` keeps its position: the best endpoint of Garland and
// Heckbert's two choices, so that every vertex stays a pixel centre and the exact integer
// predicates and the renderer apply unchanged (the optimum position would leave the grid:
// that needs the explicit fixed-point positions the scattered-samples work brings).
//
// A collapse is legal when (canCollapse):
// - link condition: the vertices adjacent to both a and b are exactly e's l and r, so the mesh
//   stays a manifold disk;
// - the rectangle is kept: corners never go; a border vertex goes only along its side, into
//   its neighbour on that side, over a boundary edge;
// - no fold-over: every triangle around `from` that stays is still positive with `to` in its
//   place (exact integer orientation).
// Removed edges are marked (their record's `a` = kNone) and dropped by compactEdges.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh.h"

namespace ddt {

// The edges at each vertex, which collapses keep up to date (the serial simplifier's
// adjacency; the record structure alone would need a walk around the vertex).
struct VertexEdges {
    std::vector<std::vector<uint32_t>> at;  // per vertex id: the ids of its edges

    explicit VertexEdges(const Mesh& mesh);
};

// A collapse of edge e: `from` is its endpoint b (b into a), or a (a into b).
struct Collapse {
    uint32_t edge = kNone;
    bool b_into_a = true;

    uint32_t from(const Mesh& mesh) const { return b_into_a ? mesh.vertices[edge].b : mesh.vertices[edge].a; }
    uint32_t to(const Mesh& mesh) const { return b_into_a ? mesh.vertices[edge].a : mesh.vertices[edge].b; }
};

bool canCollapse(const Mesh& mesh, const VertexEdges& edges, Collapse collapse);

// Performs a legal collapse (see canCollapse).
void collapseEdge(Mesh& mesh, VertexEdges& edges, Collapse collapse);

// Whether edge e was removed by a collapse.
inline bool removedEdge(const Mesh& mesh, uint32_t e) { return mesh.vertices[e].a == kNone; }

// Drops the removed edges and numbers the rest in their old order (a stable prefix sum, so
// that ties broken by id keep their meaning), updating every neighbour link.
void compactEdges(Mesh& mesh);

}  // namespace ddt
