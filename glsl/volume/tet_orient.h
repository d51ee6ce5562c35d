// The exact orientation test of the tetrahedral mesh (core/volume/tet_mesh.h), written once in
// the common subset of C++ and GLSL (GLSL needs GL_EXT_shader_explicit_arithmetic_types_int64
// before including it).
//
// Vertices sit at voxel centres, integer index coordinates in [0, kMaxTetMeshSide). Headroom of
// tetOrient: each coordinate difference lies in (−2^16, 2^16), each 2 × 2 minor below 2^33 in
// magnitude, each of the three products below 2^49, their sum below 2^51 — exact in int64, with
// no wide arithmetic (GLSL has no 128-bit integers). Larger volumes are split into bricks.
#ifndef DDTUP_TET_ORIENT_H
#define DDTUP_TET_ORIENT_H

#ifdef __cplusplus
#include <cstdint>
namespace ddt {
typedef uint32_t uint;
#define DDT_FN inline
#else
#define DDT_FN
#endif

// The widest a tetrahedral mesh may be along any axis, in vertices (voxels).
const uint kMaxTetMeshSide = 1u << 16;

// Six times the signed volume of (a, b, c, d): det[b − a, c − a, d − a], positive when
// (b − a, c − a, d − a) is a right-handed frame. Exact (see the headroom above).
DDT_FN int64_t tetOrient(int ax, int ay, int az, int bx, int by, int bz,
                         int cx, int cy, int cz, int dx, int dy, int dz) {
    const int64_t ux = bx - ax, uy = by - ay, uz = bz - az;
    const int64_t vx = cx - ax, vy = cy - ay, vz = cz - az;
    const int64_t wx = dx - ax, wy = dy - ay, wz = dz - az;
    return ux * (vy * wz - vz * wy) - uy * (vx * wz - vz * wx) + uz * (vx * wy - vy * wx);
}

#ifdef __cplusplus
}  // namespace ddt
#endif
#undef DDT_FN
#endif
