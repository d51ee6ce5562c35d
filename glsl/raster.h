// Exact sampling of the mesh at output pixels, shared by core/image/render.cpp and the render
// kernel (GLSL needs GL_EXT_shader_explicit_arithmetic_types_int64 before including it).
//
// Output pixel X (of out_size) samples the input at u = (X + 0.5) / s − 0.5 with the realised
// factor s = out_size / in_size, clamped into the hull [0, in_size − 1]. In units of
// 1 / (2 · out_size) that is the integer U = (2X + 1) · in_size − out_size, so every
// coverage test below is exact integer arithmetic: no gaps, no double coverage.
#ifndef DDTUP_RASTER_H
#define DDTUP_RASTER_H

#ifdef __cplusplus
#include <cstdint>
namespace ddt {
typedef uint32_t uint;
#define DDT_FN inline
#else
#define DDT_FN
#endif

// Sample coordinate of output column/row `index`, clamped into the hull, in units of
// 1 / (2 · out_size).
DDT_FN int64_t sampleCoord(uint index, uint in_size, uint out_size) {
    int64_t u = (2 * int64_t(index) + 1) * int64_t(in_size) - int64_t(out_size);
    int64_t hull_end = 2 * int64_t(out_size) * int64_t(in_size - 1);
    return u < 0 ? int64_t(0) : (u > hull_end ? hull_end : u);
}

// Vertex coordinate `x` (integer, input units) in the units of sampleCoord.
DDT_FN int64_t vertexCoord(uint x, uint out_size) { return 2 * int64_t(out_size) * int64_t(x); }

// First and last output index whose clamped sample lies in [lo, hi] (input units, integers).
DDT_FN uint firstSampleAtOrAfter(uint lo, uint in_size, uint out_size) {
    if (lo == 0) return 0;
    // (2X + 1)·in − out >= 2·out·lo  <=>  X >= (2·out·lo + out − in) / (2·in)
    int64_t num = 2 * int64_t(out_size) * int64_t(lo) + int64_t(out_size) - int64_t(in_size);
    int64_t den = 2 * int64_t(in_size);
    return uint((num + den - 1) / den);
}
DDT_FN uint lastSampleAtOrBefore(uint hi, uint in_size, uint out_size) {
    if (hi >= in_size - 1) return out_size - 1;
    int64_t num = 2 * int64_t(out_size) * int64_t(hi) + int64_t(out_size) - int64_t(in_size);
    return uint(num / (2 * int64_t(in_size)));
}

// Which side of the directed edge p→q the sample (su, sv) lies on: +1 left (inside a
// positive triangle), −1 right. A sample exactly on the line is pushed by (dir_u·ε, dir_v·ε²)
// for an infinitesimal ε, which decides every tie consistently, so each sample belongs to
// exactly one triangle. dir_u/dir_v are ±1 and point into the hull (see sampleDirection).
// Magnitudes: per axis |q − p| and |s − p| are at most 2 · out · in, so each product stays
// below 2^62 while out_w · out_h · in_w · in_h < 2^60 (checked by checkOutputSize).
DDT_FN int sampleSide(int64_t px, int64_t py, int64_t qx, int64_t qy, int64_t su, int64_t sv, int dir_u, int dir_v) {
    int64_t e = (qx - px) * (sv - py) - (qy - py) * (su - px);
    if (e != 0) return e > 0 ? 1 : -1;
    int64_t du = -(qy - py) * int64_t(dir_u);  // dE/du pushed along u
    if (du != 0) return du > 0 ? 1 : -1;
    return (qx - px) * int64_t(dir_v) > 0 ? 1 : -1;
}

// Push direction of a sample: into the hull, i.e. backwards on its far edge.
DDT_FN int sampleDirection(int64_t s, uint in_size, uint out_size) {
    return s == vertexCoord(in_size - 1, out_size) ? -1 : 1;
}

#ifdef __cplusplus
}  // namespace ddt
#endif
#undef DDT_FN
#endif
