// The value of a Garland–Heckbert quadric at a point (core/simplify/quadric.h), written once in
// the common subset of C++ and GLSL: core's Quadric::at and the simplification kernels include
// this file, so a collapse costs the same, bit for bit, on the CPU and on any Vulkan device
// (`precise`: no fused multiply-add, as C++ compiled for x86-64 without -mfma).
#ifndef DDTUP_QUADRIC_VALUE_H
#define DDTUP_QUADRIC_VALUE_H

#ifdef __cplusplus
#include <cstdint>
namespace ddt {
typedef uint32_t uint;
#define DDT_FN inline
#define DDT_PRECISE
#define DDT_CONST const
#else
#define DDT_FN
#define DDT_PRECISE precise
#define DDT_CONST
#endif

// Points have at most this many coordinates: x, y and up to four channels.
const uint kMaxQuadricDimensions = 6u;
// A's upper triangle, stored row by row.
const uint kQuadricUpperSize = kMaxQuadricDimensions * (kMaxQuadricDimensions + 1u) / 2u;

// Positions (in pixels) enter a quadric's point times this weight, against colour values in
// [0, 1]: core/simplify/quadric.h measures it.
const double kPositionWeight = 4.0;

// Index of A[i][j], i <= j, in the upper triangle.
DDT_FN uint quadricIndex(uint i, uint j) { return i * kMaxQuadricDimensions - i * (i - 1u) / 2u + (j - i); }

// Q(v) = vᵀAv + 2bᵀv + c for a point v of n coordinates, never below 0 (rounding is clamped
// away; a comparison rather than max(), whose choice between 0 and −0 GLSL leaves open).
DDT_FN double quadricValue(DDT_CONST double a[kQuadricUpperSize], DDT_CONST double b[kMaxQuadricDimensions], double c,
                           DDT_CONST double v[kMaxQuadricDimensions], uint n) {
    DDT_PRECISE double sum = c;
    for (uint i = 0u; i < n; ++i) {
        DDT_PRECISE double diagonal = 2.0 * b[i] * v[i] + a[quadricIndex(i, i)] * v[i] * v[i];
        sum += diagonal;
        for (uint j = i + 1u; j < n; ++j) {
            DDT_PRECISE double cross = 2.0 * a[quadricIndex(i, j)] * v[i] * v[j];
            sum += cross;
        }
    }
    return sum > 0.0 ? sum : 0.0;
}

// Whether a collapse costing `cost` over the merged quadrics' `area` errs beyond `limit`: the
// squared root-mean-square distance to their planes that is allowed (simplifySerial's
// max_error E, in 8-bit levels, gives limit = (E / 255)²); 0: no limit.
DDT_FN bool exceedsErrorLimit(double cost, double area, double limit) {
    DDT_PRECISE double allowed = limit * area;
    return limit > 0.0 && area > 0.0 && cost > allowed;
}

#ifdef __cplusplus
}  // namespace ddt
#endif
#undef DDT_FN
#undef DDT_PRECISE
#undef DDT_CONST
#endif
