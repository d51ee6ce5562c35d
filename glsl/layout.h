// Layouts and constants shared by the Vulkan host side (compute/) and the kernels (glsl/).
//
// The per-edge and per-vertex arrays are storage texel buffers (imageLoad/imageStore):
// - a texel buffer view is limited in elements (2^27 on lavapipe), not bytes, so the edge
//   arrays of a 2048² input (200 MB) fit in one binding, where a storage buffer binding
//   would stop at 128 MiB (maxStorageBufferRange);
// - lavapipe (Mesa 22.3) loads storage buffers lane by lane, but texel buffers with vector
//   gathers: a uvec4 record loads ~5× faster (bench/ measurements in the README).
// The small control block and the indirect arguments are storage buffers. Scalars travel
// in push constants.
#ifndef DDTUP_LAYOUT_H
#define DDTUP_LAYOUT_H

#ifdef __cplusplus
#include <algorithm>
#include <cstdint>
namespace ddt {
typedef uint32_t uint;
using std::min;
#endif

// Invocations per workgroup of every kernel.
const uint kGroupSize = 64;
// Vulkan guarantees 65535 workgroups per dimension.
const uint kMaxGroups = 65535;
// Items (edges, list entries) one invocation handles, at most, below 67 M items. Beyond the
// cost of a workgroup, this bounds the loop iterations of an invocation: lavapipe (llvmpipe)
// ends every loop of a shader once all its loops together have run 65535 iterations
// (LP_MAX_TGSI_LOOP_ITERATIONS), silently. A select round in the 3-region runs up to 84
// inner iterations per item, so 16 items stay far below; a 2048² ExpROI round handled with
// 823 items per invocation lost decisions and corrupted the mesh.
const uint kItemsPerInvocation = 16;
// Pixels are supersampled kSupersampling × kSupersampling by the reconstruction (as
// core/image/reconstruct.h, which the host checks against).
const uint kSupersamplingFactor = 3;
// core/image/reconstruct.h's kRelaxation: SART's step factor.
#ifdef __cplusplus
constexpr  // a float const is not a C++ constant expression
#else
const
#endif
float kSartRelaxation = 1.5;

// Candidate status of an edge during one iteration.
const uint kStatusNone = 0;       // not a candidate
const uint kStatusUndecided = 1;  // candidate, not yet accepted or rejected
const uint kStatusAccepted = 2;
const uint kStatusRejected = 3;
// A round-list entry with this bit only copies its decision into the other status array.
const uint kCopyEntry = 0x80000000u;

// Phase of the optimisation state machine kept on the device (see glsl/image/plan.comp).
const uint kPhaseCandidates = 0;  // next: evaluate candidates of a new iteration
const uint kPhaseRounds = 1;      // next: accept/reject rounds, then the flip
const uint kPhaseDone = 2;        // converged (or stopped by a safety cap)

// Slots of the indirect dispatch arguments (16 bytes apart).
const uint kArgsCandidates = 0;
const uint kArgsSelect = 1;
const uint kArgsFlip = 2;
const uint kArgsCount = 3;

// Descriptor bindings (set 0). Texel formats: records rgba32ui; lists, statuses, marks and
// spans r32ui; doubles (gains, partial sums) rg32ui holding the two halves of the double;
// luma and alpha r32f; pixels rgba32f, one texel per vertex; the rendered band rgba32f, one
// texel per output pixel (one store per pixel: lavapipe stores lane by lane).
const uint kBindingEdgeVertices = 0;    // per edge (a, b, l, r), see core/image/mesh.h
const uint kBindingEdgeNeighbours = 1;  // per edge (bl, la, ar, rb)
const uint kBindingLuma = 2;            // per vertex
const uint kBindingAlpha = 3;           // per vertex, read only when has_alpha
const uint kBindingGain = 4;            // per edge, valid for candidates
const uint kBindingStatus0 = 5;         // per edge, ping-pong between rounds
const uint kBindingStatus1 = 6;
const uint kBindingMark = 7;            // per edge: the last iteration that listed it as active, and how (keptMark in glsl/image/common.glsl)
const uint kBindingActiveList0 = 8;     // edges to test, by iteration parity
const uint kBindingActiveList1 = 9;
const uint kBindingCandidateList = 10;  // candidates of the current iteration
const uint kBindingRoundList0 = 11;     // round work, by round parity
const uint kBindingRoundList1 = 12;
const uint kBindingPixels = 13;         // input image, premultiplied
const uint kBindingBand = 14;           // rendered rows
const uint kBindingRowSpans = 15;       // per edge row: first and last vertex row touched; then the widest triangle
const uint kBindingPartialSums = 16;    // per workgroup of edge_cost
const uint kBindingControl = 17;        // storage buffer: Control
const uint kBindingArgs = 18;           // storage buffer: kArgsCount indirect dispatch arguments
// The consistent reconstruction (glsl/image/reconstruct/). Supersamples: kSupersampling² per input
// pixel, (3w) × (3h) row-major. A half-edge 2e + side is edge e seen from its left (0) or
// right (1) triangle; each triangle owns the three half-edges facing it.
const uint kBindingHits = 19;               // per supersample, rgba32ui: triangle slot, then λ0..λ2 as float bits
const uint kBindingSupersamples = 20;       // per supersample: the surface, later Dᵀ of the residual
const uint kBindingBetweenAxes = 21;        // (3w) × h: the separable passes' intermediate
const uint kBindingResidual = 22;           // per input pixel: y − D(S) (or 1 for the weights)
const uint kBindingTaps = 23;               // r32f: the x taps, then the y taps
const uint kBindingHalfEdgeValueSums = 24;  // per half-edge: its triangle's ⟨λ of the vertex facing it, ρ⟩
const uint kBindingHalfEdgeBubbleSums = 25; // per half-edge: its triangle's ⟨4 λp λq of its edge, ρ⟩
const uint kBindingSurfaceValues = 26;      // per vertex: the reconstructed values
const uint kBindingValueLow = 27;           // per vertex: the bounds of the values
const uint kBindingValueHigh = 28;
const uint kBindingValueWeights = 29;       // per vertex: SART's normaliser ⟨φ, Dᵀ1⟩
const uint kBindingBubbles = 30;            // per edge
const uint kBindingBubbleWeights = 31;      // per edge: ⟨φ, Dᵀ1⟩
const uint kBindingStarStart = 32;          // r32ui per vertex: its lowest-id edge, where its star walk starts
// Explicit positions (core/image/mesh.h), read by the kernels that evaluate costs when kPositioned.
const uint kBindingPositions = 33;          // rg32i per vertex: its Position (glsl/fixed_position.h)
// The convolution fallback (glsl/image/fallback/), r32f per input pixel.
const uint kBindingFallbackWeights = 34;    // the surface's weight w(p); first the gradient energy
const uint kBindingFallbackAcross = 35;     // the energy smoothed along x, while the weights are made
const uint kBindingAcceptedList = 36;       // r32ui: the current iteration's accepted candidates, as select decides them
const uint kBindingCount = 37;

// Counters and state of the optimisation, written by the kernels, read by the host after
// each submit. Counters that kernels append to are updated with atomics.
struct Control {
    uint phase;
    uint iteration;            // index of the current iteration
    uint round;                // accept/reject rounds done in the current iteration
    uint candidate_count;      // candidates of the current iteration (= entries of the candidate list)
    uint active_count[2];      // entries of active list [iteration & 1]
    uint round_count[2];       // entries of round list [round & 1] (copy entries included)
    uint undecided_count[2];   // undecided entries among them
    uint flips_in_iteration;   // flips of the current iteration (= entries of the accepted list)
    uint capped;               // 1: a safety cap stopped the optimisation
    uint total_rounds;
    uint max_rounds_in_iteration;
    uint total_flips_low;      // 64-bit total as two words (no 64-bit atomics needed)
    uint total_flips_high;
};

// Push constants of every kernel: the job's scalars, then the kernel-specific ones.
struct PushConstants {
    uint width;
    uint height;
    uint edge_count;
    uint has_alpha;
    uint active_set;           // 1: after the first iteration test only the active list
    uint exproi_iterations;    // ROI is the 3-region in iterations below this, else the 2-region
    uint max_iterations;       // safety caps, reported when reached
    uint max_rounds;
    uint channels;
    uint step;                 // plan: which step to plan (kArgs…); edge_cost: 1 stores every cost;
                               // reconstruction updates: 0 stores the weights, 1 applies a SART step
    uint first_edge_row;       // render: the first edge row of the dispatch (its y dimension)
    uint first_row;            // render, fallback blend: the band's output rows
    uint row_count;
    uint first_col;            // render: the window's output columns
    uint col_count;
    uint out_width;            // render, fallback blend: the whole output's size
    uint out_height;
    uint input_width;          // render, fallback blend: the whole input's size (the job is its crop at crop_x, crop_y)
    uint input_height;
    uint crop_x;
    uint crop_y;
    uint band_first_col;       // render, fallback blend: the band's first output column and its width in pixels
    uint band_width;
    uint quadratic;            // render: 1 renders the reconstructed surface (values and bubbles)
    uint taps_x_radius;        // reconstruction: the degradation's taps per axis, 2r + 1 each
    uint taps_y_radius;
    uint integer_samples;      // reconstruction, fallback blend: 1 bounds the values to [0, 1] (8- and 16-bit input)
    float quantisation_tolerance;  // reconstruction: residuals count beyond this (core/image/reconstruct.h)
    float grain_share;             // fallback weights: the share grain keeps (core/image/convolution_fallback.h)
};

// Workgroups for `count` items: kItemsPerInvocation per invocation, more only past
// kMaxGroups groups (kernels loop over the range).
#ifdef __cplusplus
inline
#endif
uint groupsFor(uint count) {
    const uint per_group = kGroupSize * kItemsPerInvocation;
    return min(count / per_group + (count % per_group != 0 ? 1u : 0u), kMaxGroups);
}

#ifdef __cplusplus
static_assert(sizeof(Control) == 16 * 4, "Control layout");
static_assert(sizeof(PushConstants) == 29 * 4, "PushConstants layout");
}  // namespace ddt
#endif
#endif
