// Half-edge collapses on the edge-centric mesh (core/image/mesh.h), the step of simplification.
//
// Collapsing vertex `from` into its neighbour `to` along edge e = (a, b) removes `from`, e, the
// triangles (a, b, l) and (b, a, r) and, of each, the edge from–l (from–r), whose outer side
// the edge to–l (to–r) takes over. `to` keeps its position, or moves to a given one (the
// merged vertex's best place, core/simplify/placement.h) on a mesh with explicit positions.
//
// A collapse is legal when (canCollapse):
// - link condition: the vertices adjacent to both a and b are exactly e's l and r, so the mesh
//   stays a manifold disk;
// - the rectangle is kept: corners never go; a border vertex goes only along its side, into
//   its neighbour on that side, over a boundary edge; a vertex on a locked side
//   (Mesh::locked_sides) counts as a corner: it neither goes nor moves;
// - the hull is kept (a triangulation of samples covers their convex hull, not the rectangle;
//   on the grid's mesh these are the rectangle's rules again): a vertex on the hull goes only
//   over a hull edge, into its neighbour there, and only where it lies on one line with its
//   two hull neighbours (hullPlaceOf: straight); a corner of the hull never goes. A merged
//   vertex on the hull moves only along the rectangle's side it lies on (the hull is that
//   side there); elsewhere on the hull, or at a hull corner, it stays at `to`'s place;
// - no fold-over: every triangle around `from` that stays is still positive with `to` in its
//   place (exact integer orientation).
// - valence: `to` ends with at most kMaxCollapseValence edges (see there).
// Removed edges are marked (their record's `a` = kNone) and dropped by compactEdges.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh.h"

namespace ddt {

// The most edges a collapse may leave at a vertex. It bounds the walks of the legality test
// (the link condition visits deg(from) · deg(to) pairs), which a Vulkan kernel must keep
// within lavapipe's loop budget (glsl/layout.h). Reached only in flat regions, whose vertices
// collapse into fans: on the bench's photographs no vertex has more than 21 edges at any
// share, on its drawings up to 161 without the bound.
constexpr uint32_t kMaxCollapseValence = 64;

// The sides of the rectangle position p lies on (rectangleSides), with kLockedSide added where
// one of them is locked: a vertex there has two bits set, as a corner has, and the rules below
// keep it as they keep a corner.
constexpr uint32_t kLockedSide = 1u << 4;
inline uint32_t collapseSides(const Mesh& mesh, Position p) {
    const uint32_t sides = rectangleSides(mesh, p);
    return sides & mesh.locked_sides ? sides | kLockedSide : sides;
}
inline uint32_t collapseSides(const Mesh& mesh, uint32_t v) { return collapseSides(mesh, positionOf(mesh, v)); }
inline bool lockedVertex(const Mesh& mesh, uint32_t v) { return (rectangleSides(mesh, v) & mesh.locked_sides) != 0; }

// One edge at each vertex, from which a walk over the edge records reaches the vertex's other
// edges (forEachEdgeAt); collapses keep it valid. A walk rather than per-vertex lists because
// it is what a Vulkan kernel can do with fixed-size records: the simplifiers then read the
// mesh as the kernels will.
struct VertexEdges {
    std::vector<uint32_t> first;  // per vertex id: one of its edges; kNone where no edge is left

    explicit VertexEdges(const Mesh& mesh);
};

// The edge after f around its endpoint v: counter-clockwise (y up) across f's triangle on that
// side, or clockwise; kNone at the hull.
inline uint32_t turnAround(const Mesh& mesh, uint32_t v, uint32_t f, bool counter_clockwise) {
    const EdgeNeighbours& n = mesh.neighbours[f];
    // At a, the left triangle (a, b, l) follows ab counter-clockwise; at b, the right one (b, a, r).
    if (mesh.vertices[f].a == v) return counter_clockwise ? n.la : n.ar;
    return counter_clockwise ? n.rb : n.bl;
}

// Calls visit(f) once for every edge f at vertex v: counter-clockwise from edges.first[v] and,
// where that reaches the hull, clockwise from it too.
template <typename Visit>
void forEachEdgeAt(const Mesh& mesh, const VertexEdges& edges, uint32_t v, Visit visit) {
    const uint32_t start = edges.first[v];
    if (start == kNone) return;
    uint32_t f = start;
    do {
        visit(f);
        f = turnAround(mesh, v, f, true);
    } while (f != kNone && f != start);
    if (f == kNone)
        for (f = turnAround(mesh, v, start, false); f != kNone; f = turnAround(mesh, v, f, false)) visit(f);
}

// Where vertex v lies on the mesh's hull: not on it; on a straight stretch (on one line with
// its two hull neighbours, as a side's vertex of the rectangle); or at a corner of it. A
// collapse may remove a straight one without changing the hull, never a corner.
enum class HullPlace { inside, straight, corner };
HullPlace hullPlaceOf(const Mesh& mesh, const VertexEdges& edges, uint32_t v);

// A collapse of edge e: `from` is its endpoint b (b into a), or a (a into b). The merged
// vertex stays at `to`'s place, or, if `moves`, goes to `target`.
struct Collapse {
    uint32_t edge = kNone;
    bool b_into_a = true;
    bool moves = false;
    Position target = {0, 0};

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
