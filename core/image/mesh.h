// The triangulation of the pixel grid, stored edge-centric as in the paper's Sec. 4.1.
//
// Glossary (the code uses these words only in these senses):
// - vertex: id = y * width + x, first at the pixel centre (x, y); y grows downwards. The grid's
//   vertices stay there (positions empty: the fast special case). A simplified mesh
//   (core/simplify/) uses a subset of the ids, and may move them: then `positions` holds each
//   vertex's place in fixed point (glsl/fixed_position.h); its edges are any triangulation of
//   the used vertices that covers the grid's rectangle [0, w − 1] × [0, h − 1].
//   A triangulation of samples (core/delaunay/) covers the convex hull of its vertices
//   instead: known pixels of a masked image (a subset of the grid's ids, at their centres), or
//   points anywhere in the rectangle (ids 0 … n − 1 with n explicit positions).
// - orientation: orient(p, q, r) = (q - p) × (r - p) = (qx-px)(ry-py) - (qy-py)(rx-px).
//   "Positive" triangles have orient > 0 (counter-clockwise in a y-up frame, clockwise on
//   screen). Every triangle of a valid mesh is positive.
// - main vertices of an edge: its endpoints a, b. adjacent vertices: l, the third vertex of
//   the left triangle (a, b, l), and r, of the right triangle (b, a, r); both triangles are
//   positive. A boundary edge (on the hull) has only one of them, the other is kNone.
// - neighbour edges: the other edges of those triangles, kept in the order
//   bl (b–l), la (l–a), ar (a–r), rb (r–b); kNone on the missing side.
// - 1-region of e: its neighbour edges. n-region: the (n−1)-region plus the neighbours of its
//   edges. ROI (region of influence): the edges whose flip can change e's gain — for
//   Sederberg's cost and face-SCF the 2-region, 12 edges, e itself excluded (the gain reads
//   the records of e and its neighbours); for variance the 1-region (the gain reads e's record
//   only; core/image/cost.h roiDegree). closed n-region: the n-region plus e. The parallel rules'
//   conflict region is the 2-region (ExpROI: the 3-region) for every cost: besides the ROI, it
//   keeps accepted flips from writing one record (glsl/image/select.comp).
// - far vertex of a neighbour edge: its adjacent vertex on the side away from e.
// - flip of e: the quadrilateral a, r, b, l gets its other diagonal. Stored as a rotation of
//   the record: (a, b, l, r) -> (r, l, a, b), neighbours (bl, la, ar, rb) -> (la, ar, rb, bl).
//   The edge keeps its id. Only e's record and the facing halves of its four neighbours'
//   records change (its closed 1-region).
//
// Edge ids are stable and fixed by the initial grid: vertices in row-major order, for each
// vertex its edge to the right, then down, then the diagonal to (x+1, y+1) (paper Fig. 7).
// This fixes the serial sweep order and the parallel variants' id keys.
//
// The arrays are structure-of-arrays and are uploaded to the GPU as they are.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fixed_position.h"
#include "sederberg.h"

namespace ddt {

struct EdgeVertices {
    uint32_t a, b, l, r;
};

struct EdgeNeighbours {
    uint32_t bl, la, ar, rb;
};

// What a mesh's boundary must be: the rectangle [0, w − 1] × [0, h − 1] (the grid's mesh and
// its simplifications), or the convex hull of its vertices (a triangulation of samples,
// core/delaunay/).
enum class MeshHull { rectangle, convex };

struct Mesh {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<EdgeVertices> vertices;
    std::vector<EdgeNeighbours> neighbours;
    // Per vertex id, where explicit (see the glossary); empty: every vertex at its pixel centre.
    std::vector<Position> positions;
    // The sides of the rectangle (rectangleSides' bits) whose vertices a simplification keeps
    // where they are: a tile's sides shared with its neighbours, so that the tiles' meshes
    // still join (app/simplified_upscale.h). 0 for a whole picture.
    uint32_t locked_sides = 0;
    // A triangulation of samples covers their convex hull: a simplification keeps that hull and
    // fits the kept vertices' colours to the samples rather than to every pixel (core/simplify/).
    MeshHull hull = MeshHull::rectangle;

    uint32_t edgeCount() const { return uint32_t(vertices.size()); }
    // Vertex ids run below this: the grid's w·h, or one per explicit position.
    uint32_t vertexCount() const { return positions.empty() ? width * height : uint32_t(positions.size()); }
};

// Vertex v's position (explicit, or its pixel centre's; the sides must then be at most
// kMaxPositionedSide).
inline Position gridPosition(uint32_t v, uint32_t width) {
    return {int32_t(v % width) * kPositionOne, int32_t(v / width) * kPositionOne};
}
inline Position positionOf(const Mesh& mesh, uint32_t v) {
    return mesh.positions.empty() ? gridPosition(v, mesh.width) : mesh.positions[v];
}
// Where the cost formulas (glsl/image/sederberg.h) find the mesh's vertices: the explicit positions,
// or, without them, the pixel centres of the width × height grid.
inline Places placesOf(const Mesh& mesh) {
    return {mesh.width, mesh.positions.empty() ? nullptr : mesh.positions.data()};
}

// Gives every vertex its explicit position, its pixel centre's (a no-op if it has them).
// Needs sides of at most kMaxPositionedSide.
void makePositionsExplicit(Mesh& mesh);

// The sign of orient(p, q, r) at the vertices' positions (positionOf): +1, 0 or −1, exact.
int orientationSign(const Mesh& mesh, uint32_t p, uint32_t q, uint32_t r);

// The sides of the rectangle position p lies on: bit 0 x = 0, 1 x = w − 1, 2 y = 0, 3 y = h − 1.
uint32_t rectangleSides(const Mesh& mesh, Position p);
inline uint32_t rectangleSides(const Mesh& mesh, uint32_t v) { return rectangleSides(mesh, positionOf(mesh, v)); }

// Number of edges of the grid triangulation of a width × height image.
uint64_t gridEdgeCount(uint32_t width, uint32_t height);

// The initial triangulation: every grid cell split by the diagonal (x, y)–(x+1, y+1).
// Needs width, height >= 2.
Mesh buildGridMesh(uint32_t width, uint32_t height);

// The mesh of `triangles` (three vertex ids each, positive) over the width × height grid's
// vertices: edges numbered in the order the triangles first name them. For triangulations
// made elsewhere (a peer's simplifier in the bench); checkMesh says whether they are valid.
Mesh meshFromTriangles(uint32_t width, uint32_t height, const std::vector<uint32_t>& triangles);

// Flips edge e (the caller checks that its quadrilateral is strictly convex).
void flipEdge(Mesh& mesh, uint32_t e);

// The vertices a flip of e reads: its quadrilateral and the far vertices of its neighbours.
FlipStencil flipStencil(const Mesh& mesh, uint32_t e);

// Far vertex of neighbour edge `neighbour` as seen from the triangle whose third vertex is
// `near` (kNone if the neighbour is kNone or a boundary edge).
inline uint32_t farVertex(const Mesh& mesh, uint32_t neighbour, uint32_t near) {  // inline: four per flip gain
    if (neighbour == kNone) return kNone;
    const EdgeVertices& v = mesh.vertices[neighbour];
    return v.l == near ? v.r : v.l;
}

// The neighbours of e (kNone entries included), in bl, la, ar, rb order.
inline uint32_t neighbourAt(const EdgeNeighbours& n, int i) {
    return i == 0 ? n.bl : i == 1 ? n.la : i == 2 ? n.ar : n.rb;
}

// The ROI of e: its 2-region (degree 2) or 3-region (degree 3), e excluded, each edge once,
// sorted by id.
std::vector<uint32_t> regionOf(const Mesh& mesh, uint32_t e, int degree);

// A triangle of the mesh, positive, listed once: it is reported by the lowest-id edge among
// its three edges. e0, e1, e2 are its edges opposite v0, v1, v2.
struct Triangle {
    uint32_t v0, v1, v2;
    uint32_t e0, e1, e2;
};
std::vector<Triangle> listTriangles(const Mesh& mesh);

// Calls f(triangle) for every triangle that edges [first, end) report, in listTriangles' order.
template <typename F>
void forEachTriangle(const Mesh& mesh, uint32_t first, uint32_t end, F f) {
    for (uint32_t e = first; e < end; ++e) {
        const EdgeVertices& v = mesh.vertices[e];
        const EdgeNeighbours& n = mesh.neighbours[e];
        if (v.l != kNone && e < n.bl && e < n.la) f(Triangle{v.a, v.b, v.l, n.bl, n.la, e});
        if (v.r != kNone && e < n.ar && e < n.rb) f(Triangle{v.b, v.a, v.r, n.ar, n.rb, e});
    }
}
// Calls f(triangle) for every triangle, in listTriangles' order.
template <typename F>
void forEachTriangle(const Mesh& mesh, F f) {
    forEachTriangle(mesh, 0, mesh.edgeCount(), f);
}

// Checks the mesh: every record consistent with its neighbours, every triangle positive,
// interior edges shared by two triangles, boundary edges with one forming a single convex
// loop that the triangles fill exactly, Euler's count for a disk, no duplicate edge, all at
// the vertices' positions (positionOf: sides of at most kMaxPositionedSide); for
// MeshHull::rectangle also boundary edges along the rectangle's sides and total area
// (w−1)(h−1). Returns "" if valid, else the first problem found.
std::string checkMesh(const Mesh& mesh, MeshHull hull = MeshHull::rectangle);

}  // namespace ddt
