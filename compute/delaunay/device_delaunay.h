// The Delaunay triangulation of points (core/delaunay/delaunay.h) by Lawson's flips in parallel
// on a Vulkan device, equal to the CPU reference record for record.
//
// Recipe: a first triangulation by a serial sweep on the CPU (core/delaunay/
// sweep_triangulation.h); then rounds on the device (glsl/delaunay/) — mark the edges of the
// round's work list that are not locally Delaunay, select those whose priority is least among
// the marked edges of their two triangles, flip them, list the edges whose quadrilaterals
// changed and the marked ones that lost for the next round — until a round marks none; then
// the canonical numbering (core/delaunay/canonical_edges.h) on the CPU.
//
// Why the result equals delaunayOfPoints': the marks use the same perturbed predicate
// (glsl/delaunay/in_circle.h, checked against predicates.h by the tests), under which no four
// points are cocircular: the lifted points lie on a strictly convex surface in general
// position. Each flip of an edge that is not locally Delaunay replaces two triangles by the
// two below them in the lift (a tetrahedron of the lifted points is passed), so the lifted
// surface only goes down and no triangulation repeats: the flips stop, after at most one flip
// per pair of points (an edge flipped away never comes back). A round with a mark flips at least
// its marked edge of least priority, so the rounds stop too. The lists miss no edge to flip: an
// edge off a round's list was found locally Delaunay by its last marks, and a flip that changes
// its quadrilateral lists it. So the last round leaves a triangulation of the convex hull with
// every interior edge locally Delaunay. By Delaunay's lemma (see checkDelaunay) it is
// then the perturbed Delaunay triangulation, which is unique: the reference's, and after the
// canonical numbering the same records.
//
// Measured on lavapipe (LP_NUM_THREADS=2, Release, a shared 2-core VM; `ddtup-bench-delaunay
// --tables delaunay --vulkan --repeats 2`, uniform points in a 4096² frame), against CGAL's
// Delaunay_triangulation_2, wall clock:
//   10^4 points: 0.040 s (17 rounds), CGAL 0.009 s
//   10^5 points: 0.22 s (20 rounds), CGAL 0.12 s
//   10^6 points: 2.4 s (22 rounds, 0.91 flips a point; sweep 0.19 s, device 1.78 s, numbering
//                0.30 s), CGAL 1.28 s
// The advancing-front sweep leaves fewer than one flip a point (the first sweep, which joined
// each point to every hull vertex it saw, left 13), and a round after the first goes through
// its work list, the edges the last one touched, not every edge.
#pragma once

#include <cstdint>
#include <vector>

#include "context.h"
#include "mesh.h"

namespace ddt {

// What a run did, for the tests and measurements.
struct DeviceDelaunayStats {
    uint32_t rounds = 0;        // rounds that flipped something
    uint64_t flips = 0;         // flips over all rounds
    double sweep_seconds = 0;   // the first triangulation, CPU
    double flip_seconds = 0;    // the device's rounds, uploads and downloads included
    double number_seconds = 0;  // the canonical numbering, CPU
};

// delaunayOfPoints(width, height, points), the same input contract and the same Mesh.
// Throws std::invalid_argument when the edge records exceed the device's texel-buffer elements
// (about 11 M points on lavapipe).
Mesh deviceDelaunayOfPoints(VulkanContext& context, uint32_t width, uint32_t height,
                            const std::vector<Position>& points, DeviceDelaunayStats* stats = nullptr);

// delaunayOfPixels(width, height, pixel_ids): the same Mesh, positions implicit.
Mesh deviceDelaunayOfPixels(VulkanContext& context, uint32_t width, uint32_t height,
                            const std::vector<uint32_t>& pixel_ids, DeviceDelaunayStats* stats = nullptr);

}  // namespace ddt
