// Bindings, constants and push constants of the resampling kernel (tet_resample.comp), shared
// with its host side (compute/volume/tet_resample_device.h). Written in the common subset of
// C++ and GLSL (GLSL includes it after GL_EXT_shader_explicit_arithmetic_types_int64).
//
// One invocation resamples one tet, as core/volume/tet_resample.cpp's loop body: the output
// samples in its vertices' box, each owned sample's value stored. A tet whose exact tests would
// need more than int64, or whose box of samples would loop too long for llvmpipe (every loop of
// an invocation together ends silently after 65 535 trips), is deferred: its bit is set and the
// host resamples it with core's code.
#ifndef DDTUP_TET_RESAMPLE_LAYOUT_H
#define DDTUP_TET_RESAMPLE_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
namespace ddt {
typedef uint32_t uint;
#endif

const uint kTetResampleGroupSize = 64u;
// Workgroups per dimension (Vulkan's guaranteed minimum); more go to a second dimension.
const uint kTetResampleMaxGroups = 65535u;

// A tet is resampled on the device when its box of samples within the window, counted as the
// rows plus the samples (the trips of the two inner loops), is at most this: half llvmpipe's
// limit, leaving room for the few short loops around them. A Kuhn tet magnified ×k per axis has
// a box of about (k + 1)³ samples, so up to about ×30 every Kuhn tet stays on the device.
const uint kTetResampleMaxBoxTrips = 32768u;
// tet_resample.h's bound for int64: |f_i| ≤ 6 · Ex · Ey · Ez < 2^62 (computed in double).
const uint kTetResampleNarrowLog2 = 62u;

// Bindings (set 0).
const uint kTetResampleBindingVertices = 0u;  // rgba32ui per slot (TetMesh::vertices)
const uint kTetResampleBindingValues = 1u;    // r32f per vertex of the mesh
// r32ui: per axis a (x, y, z in turn, n_a input voxels each) the first output index whose sample
// lies at or after input index i, then the end of those at or before it (core's SampleGrid
// tables), 2 · n_a entries per axis.
const uint kTetResampleBindingSampleRanges = 2u;
const uint kTetResampleBindingSlab = 3u;      // r32f: the slab's output voxels (x fastest)
// Storage buffer: word 0 counts the deferred tets, then bit (t % 32) of word 1 + t / 32 marks
// slot t as deferred (atomics, so a whole buffer rather than a texel view).
const uint kTetResampleBindingDeferred = 4u;
const uint kTetResampleBindingCount = 5u;

// Push constants. The slab is the part of the window this dispatch writes: rows
// [slab_begin_y, slab_end_y) of planes [slab_begin_z, slab_end_z), whole along x, stored
// x fastest from (out_begin[0], slab_begin_y, slab_begin_z).
struct TetResamplePush {
    uint mesh_size[3];      // the mesh's vertices per axis (a brick's, or the whole input's)
    uint vertex_offset[3];  // where the mesh's vertex (0, 0, 0) sits in the whole input
    uint in_size[3];        // the whole input's voxels, n per axis
    uint out_size[3];       // the whole output's voxels, m per axis
    uint out_begin[3];      // the window: output voxels [out_begin, out_end) per axis
    uint out_end[3];
    uint slab_begin_y;
    uint slab_end_y;
    uint slab_begin_z;
    uint slab_end_z;
    uint slot_count;
    uint max_box_trips;     // kTetResampleMaxBoxTrips (tests lower it to defer tets)
    uint narrow_log2;       // kTetResampleNarrowLog2 (tests lower it to defer tets)
    uint pad[3];
};

#ifdef __cplusplus
static_assert(sizeof(TetResamplePush) == 112 && offsetof(TetResamplePush, slab_begin_y) == 72,
              "TetResamplePush layout (std430 push constants: uints and arrays of uint)");
static_assert(sizeof(TetResamplePush) <= 128, "Vulkan guarantees 128 bytes of push constants");
}  // namespace ddt
#endif
#endif
