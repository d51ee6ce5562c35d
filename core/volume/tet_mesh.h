// The tetrahedralization of a voxel grid that the volume optimizer (core/volume/) improves by
// bistellar flips, after Tóth et al., "N-dimensional data-dependent reconstruction using
// topological changes" (../shared/papers/ndim-ddt-topological-changes.md).
//
// Glossary (the volume code uses these words only in these senses):
// - vertex: id = x + nx · (y + ny · z), at the voxel centre (x, y, z) of the index frame
//   (core/volume/volume.h). Vertices never move and are never removed.
// - tet: a record t of 4 vertex ids, positive: tetOrient(v0, v1, v2, v3) > 0
//   (glsl/volume/tet_orient.h), in the index frame.
// - face i of a tet: the triangle of its vertices other than vertex i. neighbour i: the tet
//   across face i, kNoTet when face i lies on the box's sides (a boundary face).
// - slot: a tet record. A free slot has vertices[t][0] == kNoTet and is listed in free_slots;
//   a 2–3 flip takes one, a 3–2 flip gives one back. Slot ids are otherwise stable.
// - edge: two vertices of a tet. Its ring: the tets around it, in order across faces; its
//   degree: how many there are. An interior edge's ring closes; a boundary edge's ring ends
//   at two boundary faces.
// - flips (bistellar, the paper's Fig. 6), each replacing the tets of a region by others on
//   the same vertices that fill the same region:
//   2–3: the face shared by tets (a, b, c, d) and (a, b, c, e) becomes the edge (d, e) with
//        three tets around it; legal when the segment d–e crosses the face's interior.
//   3–2: an interior edge of degree 3 becomes the face of its ring's three vertices; legal
//        when the edge crosses that face's interior (the inverse of 2–3).
//   4–4: an interior edge (p, q) of degree 4 whose ring a, b, c, d is coplanar becomes the
//        ring's other diagonal (a, c → b, d or the reverse); the degenerate case of 2–3 + 3–2.
//   2–2: a boundary edge of degree 2 whose two boundary faces are coplanar becomes the other
//        diagonal of their quadrilateral, on the box's side.
//   A flip is legal exactly when every new tet is positive (and, for 4–4 and 2–2, the
//   coplanarity holds): the exact predicate decides, never a tolerance.
// - the initial mesh (Kuhn / Freudenthal): each cell (x..x+1, y..y+1, z..z+1) is split into
//   six tets around its diagonal (x, y, z)–(x+1, y+1, z+1), one per order of the three axes,
//   the same way in every cell, so the faces match across cells. On each of the box's sides
//   this is the 2-D grid's triangulation (diagonals (x, y)–(x+1, y+1)).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "volume/tet_orient.h"

namespace ddt {

constexpr uint32_t kNoTet = 0xffffffffu;

using TetVertices = std::array<uint32_t, 4>;
using TetNeighbours = std::array<uint32_t, 4>;

struct TetMesh {
    std::array<uint32_t, 3> size{};  // vertices (voxels) along x, y, z; each at least 2
    std::vector<TetVertices> vertices;      // per slot
    std::vector<TetNeighbours> neighbours;  // per slot
    std::vector<uint32_t> free_slots;

    uint32_t slotCount() const { return uint32_t(vertices.size()); }
    uint32_t tetCount() const { return slotCount() - uint32_t(free_slots.size()); }
    bool inUse(uint32_t t) const { return vertices[t][0] != kNoTet; }
    uint32_t vertexCount() const { return size[0] * size[1] * size[2]; }
};

struct VertexCoordinates {
    int x, y, z;
};
inline VertexCoordinates coordinatesOf(const TetMesh& mesh, uint32_t v) {
    return {int(v % mesh.size[0]), int(v / mesh.size[0] % mesh.size[1]),
            int(v / (mesh.size[0] * mesh.size[1]))};
}

// Six times the signed volume of (a, b, c, d) in the index frame, exactly.
int64_t orientOf(const TetMesh& mesh, uint32_t a, uint32_t b, uint32_t c, uint32_t d);
inline int64_t orientOf(const TetMesh& mesh, const TetVertices& t) {
    return orientOf(mesh, t[0], t[1], t[2], t[3]);
}

// The initial mesh of a grid of size[0] × size[1] × size[2] vertices (each side from 2 to
// kMaxTetMeshSide): 6 tets per cell; slot 6 · cell + p, cell = x + (nx − 1) · (y + (ny − 1) · z),
// p the axis order's index in kAxisOrders (tet_mesh.cpp). No free slots.
TetMesh kuhnTetMesh(const std::array<uint32_t, 3>& size);

// Empty if `mesh` is a valid tetrahedralization of its box, else what is wrong first: vertex
// ids in range and distinct, the free slots exactly the unused records, every tet positive,
// neighbour links symmetric and across the same face, each face shared by two tets or lying
// on the box's sides with no neighbour, and the tets' volumes summing to the box's. Exact
// (integer) throughout; found independently of how kuhnTetMesh links neighbours.
std::string checkTetMesh(const TetMesh& mesh);

}  // namespace ddt
