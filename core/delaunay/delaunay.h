// The Delaunay triangulation of samples: known pixels of a masked image, or points anywhere in
// the frame, as a core/image/mesh.h Mesh over the convex hull of its vertices. Exact (the integer
// predicates of predicates.h) and unique: four cocircular points are decided by a symbolic
// tie-break that cuts every unit grid cell along (x, y)–(x + 1, y + 1), so the full grid's
// triangulation is buildGridMesh's, record for record. Serial: the CPU reference of a GPU
// version.
//
// Edges are numbered canonically, by (smaller vertex id, larger vertex id), with a the smaller
// and b the larger; on the full grid this is buildGridMesh's numbering.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mesh.h"

namespace ddt {

// The widest and tallest frame: its coordinates stay below 2^26, the in-circle test's range
// (predicates.h).
inline constexpr uint32_t kMaxDelaunaySide = 65536;

// Why `points` have no triangulation: "fewer than 3 points", "two points at the same place"
// or "all points are collinear"; "" if they have one.
std::string delaunayInputProblem(const std::vector<Position>& points);

// The triangulation of the width × height grid's vertices `pixel_ids` (ids y · width + x,
// ascending, distinct), each at its pixel centre: positions stay implicit.
// Needs sides of at most kMaxDelaunaySide and a valid input (delaunayInputProblem).
Mesh delaunayOfPixels(uint32_t width, uint32_t height, const std::vector<uint32_t>& pixel_ids);

// The triangulation of `points` (vertex i at points[i]), distinct, in row-major order, inside
// [0, (width − 1) · kPositionOne] × [0, (height − 1) · kPositionOne]: positions = points.
// Needs sides of at most kMaxDelaunaySide and a valid input (delaunayInputProblem).
Mesh delaunayOfPoints(uint32_t width, uint32_t height, const std::vector<Position>& points);

// "" if every interior edge of `mesh` is locally Delaunay under the perturbed predicate (the
// far vertex of its right triangle outside its left triangle's circumcircle), else the first
// edge that is not. For a triangulation of the convex hull of its vertices, locally Delaunay
// everywhere means Delaunay (Delaunay's lemma, which holds for the perturbed lifts as for any
// lifting: the lifted surface is then locally convex, hence convex). Its positions (positionOf)
// must lie in [0, 2^26).
std::string checkDelaunay(const Mesh& mesh);

}  // namespace ddt
