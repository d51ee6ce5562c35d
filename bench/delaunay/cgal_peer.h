// The CGAL peer (CGAL 5.5, header-only, this file's .cpp the only one that includes it, as it
// is slow to compile): Delaunay_triangulation_2 with Exact_predicates_inexact_constructions_kernel,
// for the Delaunay table, and Sibson's natural-neighbour interpolation on it
// (natural_neighbor_coordinates_2) for the reconstruction table.
#pragma once

#include <cstdint>
#include <vector>

#include "child_run.h"
#include "image.h"
#include "mesh.h"

namespace bench {

struct CgalTriangulation {
    uint64_t triangles = 0;
    bool valid = false;           // Delaunay_triangulation_2::is_valid: the combinatorics and empty circles
    std::vector<uint64_t> edges;  // smaller id << 32 | larger id, sorted (only when asked for)
};

// The triangulation of `points` (vertex i at points[i], coordinates in fixed-point units as
// doubles, which holds them exactly, so the predicates see the same geometry as ddtup's),
// inserted as one range so that CGAL sorts it spatially itself. The conversion to CGAL's
// points is outside `span`; the insertion, `repeats` times, inside it.
CgalTriangulation cgalDelaunay(const std::vector<ddt::Position>& points, Span& span, uint32_t repeats, bool want_edges);

// `image` with every pixel not in `known` (ids y · width + x, ascending) replaced by Sibson's
// natural-neighbour interpolation of the known pixels' values, at its pixel centre, channel by
// channel (an unknown pixel outside the known pixels' hull takes its nearest known pixel's).
ddt::Image cgalNaturalNeighbours(const ddt::Image& image, const std::vector<uint32_t>& known);

}  // namespace bench
