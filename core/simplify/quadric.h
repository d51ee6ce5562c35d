// Garland and Heckbert's quadric error metric, in the generalised form of their 1998 paper
// "Simplifying surfaces with color and texture using quadric error metrics": a mesh vertex is
// a point (x, y, colour channels) in n = 2 + channels dimensions, a triangle spans a plane
// there, and the quadric of a set of triangles gives the sum of squared distances from a point
// to their planes, Q(v) = vᵀAv + 2bᵀv + c, each plane weighted by its triangle's area.
//
// The picture is planar (all z = 0), so without colour every quadric would vanish: the colour
// axes carry the error. Positions are in input pixels times kPositionWeight (4, in
// quadric_value.h), against colour values in [0, 1]. With a weight w, a plane of colour
// gradient g (range per pixel) measures a colour error δ as δ / √(1 + (g/w)²): a large w makes
// the metric the colour error alone, a small one lets vertices slide freely along hard edges.
// Measured (PSNR against the original, five photographs at ×4 from quarter size, means): with
// the merged vertex at an endpoint, w = 1, 4 and 16 gave 23.67 dB at 10 % and 22.55, 22.55,
// 22.52 dB at 5 %; at its optimal place (placement.h), at 10 %, 23.97, 23.98 and 23.98 dB: the
// weight matters little. (With the flips run again after simplifying, since dropped, 0.25 was
// 0.2 dB worse than 4.)
#pragma once

#include <cstdint>

#include "simplify/quadric_value.h"

namespace ddt {

// Plain doubles, uploaded as they are to the simplification kernels.
struct Quadric {
    double a[kQuadricUpperSize] = {};  // A's upper triangle, row by row (quadricIndex)
    double b[kMaxQuadricDimensions] = {};
    double c = 0.0;
    double area = 0.0;  // the planes' total weight: Q(v) / area is a mean squared distance

    Quadric& operator+=(const Quadric& other);
    // Q(v) for a point v of `n` coordinates (never below 0: rounding is clamped away).
    double at(const double* v, uint32_t n) const;
    // The coordinates of v whose bits are set in `free` that minimise Q(v) with the others
    // given: a vertex's best colour where it stands (the colour axes free), or its best place
    // and colour (all free). False (v unchanged) if that block of A is singular: planes that
    // all contain a free axis, as a flat region's contain the position axes.
    bool minimiseFree(double* v, uint32_t free, uint32_t n) const;
};

// The area-weighted quadric of the plane through p, q and r (n coordinates each); `area` is
// the triangle's area in the picture (input pixels²). A degenerate triangle gives zero.
Quadric planeQuadric(const double* p, const double* q, const double* r, uint32_t n, double area);

}  // namespace ddt
