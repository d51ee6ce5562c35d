// Layouts and constants shared by the Vulkan host side (compute/) and the kernels (glsl/).
// Every buffer is reached through its device address (GL_EXT_buffer_reference): the edge
// arrays of a 2048² input exceed the 128 MiB a storage-buffer binding may cover on
// lavapipe, and addresses have no such limit. Kernels get one address in their push
// constants, that of a DeviceParams block holding all the others.
#ifndef DDTUP_LAYOUT_H
#define DDTUP_LAYOUT_H

#ifdef __cplusplus
#include <cstdint>
namespace ddt {
typedef uint32_t uint;
// A buffer reference is a 64-bit device address on the host.
#define DDT_REF(Type) uint64_t
#define DDT_BLOCK(Name) struct Name
#else
#define DDT_REF(Type) Type
#define DDT_BLOCK(Name) layout(buffer_reference, std430, buffer_reference_align = 8) buffer Name
// The arrays the blocks point to.
layout(buffer_reference, std430, buffer_reference_align = 16) buffer UVec4Array { uvec4 at[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer UintArray { uint at[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer FloatArray { float at[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer DoubleArray { double at[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer DispatchArgs { uvec3 at[]; };
#endif

// Invocations per workgroup of every kernel.
const uint kGroupSize = 64;
// Vulkan guarantees 65535 workgroups per dimension; kernels loop over larger ranges.
const uint kMaxGroups = 65535;

// Candidate status of an edge during one iteration.
const uint kStatusNone = 0;       // not a candidate
const uint kStatusUndecided = 1;  // candidate, not yet accepted or rejected
const uint kStatusAccepted = 2;
const uint kStatusRejected = 3;
// A round-list entry with this bit only copies its decision into the other status array.
const uint kCopyEntry = 0x80000000u;

// Phase of the optimisation state machine kept on the device (see glsl/plan.comp).
const uint kPhaseCandidates = 0;  // next: evaluate candidates of a new iteration
const uint kPhaseRounds = 1;      // next: accept/reject rounds, then the flip
const uint kPhaseDone = 2;        // converged (or stopped by a safety cap)

// Slots of the indirect dispatch arguments.
const uint kArgsCandidates = 0;
const uint kArgsSelect = 1;
const uint kArgsFlip = 2;
const uint kArgsCount = 3;

// Counters and state of the optimisation, written by the kernels, read by the host after
// each submit. Counters that kernels append to are updated with atomics.
DDT_BLOCK(Control) {
    uint phase;
    uint iteration;            // index of the current iteration
    uint round;                // accept/reject rounds done in the current iteration
    uint candidate_count;      // candidates of the current iteration (= entries of candidate_list)
    uint active_count[2];      // entries of active_list[iteration & 1]
    uint round_count[2];       // entries of round_list[round & 1] (copy entries included)
    uint undecided_count[2];   // undecided entries among them
    uint flips_in_iteration;   // flips of the current iteration
    uint capped;               // 1: a safety cap stopped the optimisation
    uint total_rounds;
    uint max_rounds_in_iteration;
    uint total_flips_low;      // 64-bit total as two words (no 64-bit atomics needed)
    uint total_flips_high;
    uint working_dispatches;   // dispatches that had work (the rest exited at once)
    uint pad0;
};

// Everything a kernel needs to find: buffer addresses first (8-byte aligned), then scalars.
DDT_BLOCK(DeviceParams) {
    DDT_REF(UVec4Array) edge_vertices;    // per edge (a, b, l, r), see core/mesh.h
    DDT_REF(UVec4Array) edge_neighbours;  // per edge (bl, la, ar, rb)
    DDT_REF(FloatArray) luma;             // per vertex
    DDT_REF(FloatArray) alpha;            // per vertex, read only when has_alpha
    DDT_REF(DoubleArray) gain;            // per edge, valid for candidates
    DDT_REF(UintArray) status[2];         // per edge, ping-pong between rounds
    DDT_REF(UintArray) mark;              // per edge: last iteration it was put in an active list
    DDT_REF(UintArray) active_list[2];    // edges to test, by iteration parity
    DDT_REF(UintArray) candidate_list;    // candidates of the current iteration
    DDT_REF(UintArray) round_list[2];     // round work, by round parity
    DDT_REF(Control) control;
    DDT_REF(DispatchArgs) args;           // kArgsCount indirect dispatch arguments
    DDT_REF(DoubleArray) partial_sums;    // per workgroup of edge_cost
    DDT_REF(FloatArray) pixels;           // input image, premultiplied, `channels` per vertex
    DDT_REF(FloatArray) band;             // rendered rows
    DDT_REF(UintArray) row_spans;         // per edge row: first and last vertex row touched
    uint width;
    uint height;
    uint edge_count;
    uint has_alpha;
    uint active_set;           // 1: after the first iteration test only the active list
    uint exproi_iterations;    // ROI is the 3-region in iterations below this, else the 2-region
    uint max_iterations;       // safety caps, reported when reached
    uint max_rounds;
    uint channels;
    uint max_groups;           // workgroups per dispatch; larger ranges are looped over
};

// Push constants of every kernel.
struct PushConstants {
    DDT_REF(DeviceParams) params;
    uint step;          // plan: which step to plan (kArgsCandidates, kArgsSelect, kArgsFlip)
    uint first_edge;    // render: the edges whose triangles may touch the band
    uint edge_range;
    uint first_row;     // render: the band's output rows
    uint row_count;
    uint out_width;     // render: output size
    uint out_height;
    uint pad0;
};

#ifdef __cplusplus
static_assert(sizeof(Control) == 18 * 4, "Control layout");
static_assert(sizeof(DeviceParams) == 19 * 8 + 10 * 4, "DeviceParams layout");
static_assert(sizeof(PushConstants) == 40, "PushConstants layout");
}  // namespace ddt
#endif
#undef DDT_REF
#undef DDT_BLOCK
#endif
