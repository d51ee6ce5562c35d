// The parallel flip rule for tetrahedral meshes (core/volume/tet_parallel.h) on a Vulkan device,
// in kernels of its own (glsl/volume/), equal to core's rule bit for bit: the same rounds, the
// same flips in the same slots, the same free-slot stack, the same cached costs and statistics.
// What makes them equal: the plans, gains and costs are core's formulas operation for operation
// in fp64 without fused multiply-add (glsl/volume/tet_common.glsl, tet_plan.glsl) and exact
// integer orientation (tet_orient.h); every step whose result could depend on the order of the
// invocations is order-independent (atomic maxima for the claims, state bits that list a slot
// once, sets rather than sequences for the lists); the slot allocation is a prefix sum over the
// accepted flips in owner order (tet_scan.comp), not an atomic counter.
//
// Memory: the device takes the mesh's host arrays (released page by page as each is uploaded,
// given back at the end as each is downloaded, the other device arrays released first), so the
// host and device copies of the mesh are never whole together; on an exception the mesh is left
// empty. The cost totals are summed a chunk at a time, without a host copy of the costs. Only
// what the kernels read before they write is zeroed (TetDeviceReport::zeroed_bytes).
//
// On the device: the mesh records, the cost cache (flatness; for face_scf gradients and costs;
// the contents, and the variance weight's costs, are recomputed from the records, a chunk at a
// time for the totals), the lists (active, evaluation, candidates), the claims and the
// free slots; a state machine
// (tet_plan.comp) plans each step's indirect dispatch, so a command buffer holds several rounds
// and the host reads the control block once per submit.
//
// Capacity: the slot arrays hold the initial slots plus `slack` (25 %) for 2–3 flips, each of
// which adds a tet. When a round's flips need more (the device stops before the flips), the
// arrays grow to 1.25 times the need, or 1.5 times their size if more, between submits, and the
// round goes on: the same result, a few copies later.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "context.h"
#include "tet_cost.h"
#include "tet_mesh.h"
#include "tet_parallel.h"
#include "volume/tet_layout.h"

namespace ddt {

struct TetDeviceOptions {
    uint32_t rounds_per_submit = 16;  // rounds recorded in one command buffer
    double slack = 0.25;              // spare slots at the start, as a share of the initial slots
    bool profile = false;             // time each step on the device (TetDeviceReport::step_ms)
    // Testing: every array filled with 1 bits before anything is written to it, so that a
    // kernel reading what it has not written (and was not zeroed) goes wrong on any device.
    bool poison = false;
    // false: the mesh comes back without its neighbours (mesh.neighbours empty), for a caller
    // that reads only the vertices (the resampling): no host copy of them beside the device's.
    bool return_neighbours = true;
};

// How the device run went, beyond the rule's statistics.
struct TetDeviceReport {
    uint32_t submits = 0;
    uint32_t grows = 0;      // times the slot arrays grew
    uint32_t capacity = 0;   // slots the arrays held at the end
    uint64_t device_bytes = 0;  // bytes of device memory at the end
    // Bytes zero-filled on allocation and growth: the state words of the slots in use and the
    // scan words. The rest is left as allocated, so a device whose memory is host memory
    // (lavapipe) backs only the pages the kernels write.
    uint64_t zeroed_bytes = 0;
    std::vector<double> costs;  // the device's cost cache per slot at the end (TetCosts::cost)
    double init_ms = 0.0;       // wall time of the first cache's submit (kTetStepInit)
    std::array<double, kTetStepCount> step_ms{};  // device time per step (plan and kernel), when profiling
};

// Bytes the device arrays take for `capacity` slots and `vertices` vertices with `weight`.
uint64_t tetDeviceBytes(uint64_t capacity, uint64_t vertices, TetWeight weight);
// Why the device cannot optimize a mesh of `slots` slots and `vertices` vertices ("" if it can).
std::string tetDeviceProblem(const VulkanContext& context, uint64_t slots, uint64_t vertices, TetWeight weight);

// optimizeTetMeshParallel's rounds with steps (a) to (d) on the device; the same mesh, cost and
// statistics. options.evaluate_all and options.after_round are not supported (invalid_argument).
TetParallelStats optimizeTetMeshVulkan(VulkanContext& context, TetMesh& mesh, const TetCostField& field,
                                       const TetParallelOptions& options = {}, const TetDeviceOptions& device = {},
                                       TetDeviceReport* report = nullptr);
// The same, taking the field: its values are released once the device holds them.
TetParallelStats optimizeTetMeshVulkan(VulkanContext& context, TetMesh& mesh, TetCostField&& field,
                                       const TetParallelOptions& options = {}, const TetDeviceOptions& device = {},
                                       TetDeviceReport* report = nullptr);

}  // namespace ddt
