// Explicit vertex positions (core/image/mesh.h's general mesh) in fixed point, and the exact
// orientation test on them, written once in the common subset of C++ and GLSL (GLSL needs
// GL_EXT_shader_explicit_arithmetic_types_int64 before including it).
//
// A coordinate is an integer count of 1/kPositionOne input pixels, pixel centres at multiples
// of kPositionOne, within [0, kMaxPositionedSide · kPositionOne) = [0, 2^30). Headroom of
// positionOrient: each coordinate difference lies in (−2^30, 2^30), each product below 2^60 in
// magnitude, their difference below 2^61 — exact in int64, with no wide arithmetic (GLSL has no
// 128-bit integers, and fp64 is optional). Positions are snapped to this grid when they are
// made (the simplifier's new vertices), so every fold test sees the coordinates that are kept.
#ifndef DDTUP_FIXED_POSITION_H
#define DDTUP_FIXED_POSITION_H

#ifdef __cplusplus
#include <cstdint>
namespace ddt {
typedef uint32_t uint;
#define DDT_FN inline
#else
#define DDT_FN
#endif

// Fraction bits: a position resolves 1/1024 pixel. Rendering samples are snapped to the same
// grid (core/image/render.h), moving a sample by at most 1/2048 pixel.
const int kPositionBits = 10;
const int kPositionOne = 1 << kPositionBits;
// The widest and tallest input whose mesh can hold explicit positions (2^20 = 1 048 576 pixels).
const uint kMaxPositionedSide = 1u << 20;

// A vertex's place in input pixels × kPositionOne (core/image/mesh.h's explicit positions; in the
// kernels an rg32i texel).
struct Position {
    int x;
    int y;
#ifdef __cplusplus
    bool operator==(const Position&) const = default;
#endif
};

// Twice the signed area of (p, q, r): positive for positive (core/image/mesh.h) triangles. Exact.
DDT_FN int64_t positionOrient(int px, int py, int qx, int qy, int rx, int ry) {
    return int64_t(qx - px) * int64_t(ry - py) - int64_t(qy - py) * int64_t(rx - px);
}

#ifdef __cplusplus
}  // namespace ddt
#endif
#undef DDT_FN
#endif
