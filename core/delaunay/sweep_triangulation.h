// A first triangulation of a point set, valid and close to Delaunay but not Delaunay: the
// start of the parallel flips of compute/delaunay/device_delaunay.h. Lawson's flips turn any
// triangulation of the points into the Delaunay one, so any valid start will do, but the
// closer it is, the fewer flips and rounds; this one is a serial advancing-front sweep, about
// O(n) for points already in row-major order (as delaunayOfPoints takes them), on the CPU.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh.h"

namespace ddt {

// A triangulation of the convex hull of `points` (distinct, row-major order, not all collinear:
// delaunay.h's delaunayInputProblem), every point a vertex, points on the hull's sides included.
// Vertex i is points[i] (positions = points); the edges are numbered as the sweep makes them,
// not canonically. A pixel grid comes out with its first row of cells cut as the grid path
// cuts them and every later cell by the other diagonal.
Mesh sweepTriangulation(uint32_t width, uint32_t height, const std::vector<Position>& points);

}  // namespace ddt
