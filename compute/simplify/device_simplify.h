// The parallel simplification rule (core/simplify/parallel_simplify.h) on a Vulkan device, in
// kernels of its own (glsl/simplify/), equal to core's bit for bit: every edge's best legal
// collapse (the legality walks, the exact orientation and the quadric's value are the same
// formulas, in fp64 without fused multiply-add, and the key is a cut of the cost, not a
// rounding), the winners, whose regions hold no smaller key, and their collapses with the
// quadrics' merge. Still on the host: choosing the least winners of a round (a sort of about
// 1 % of the edges, downloaded each round), and the final compaction and best colours.
#pragma once

#include <vector>

#include "buffer.h"
#include "context.h"
#include "image.h"
#include "parallel_simplify.h"
#include "simplify_kernels.h"

namespace ddt {

struct DeviceRoundSelection {
    std::vector<CollapseCandidate> candidates;  // per edge
    std::vector<uint32_t> winners;              // ascending
};

// A mesh being simplified on the device: its records, walk starts and quadrics live there.
class DeviceSimplifier {
public:
    // Uploads the mesh, its walks' starts and quadrics in `start`, and the vertex values
    // `values` (what start.points reads).
    DeviceSimplifier(VulkanContext& context, const Mesh& mesh, const SimplifyStart& start, const Image& values);
    ~DeviceSimplifier();
    DeviceSimplifier(const DeviceSimplifier&) = delete;
    DeviceSimplifier& operator=(const DeviceSimplifier&) = delete;

    // Steps 1 and 2 of a round on the current mesh.
    DeviceRoundSelection select();
    // Step 3 for `collapses` (winners of one selection, in any order).
    void collapse(const std::vector<Collapse>& collapses);
    // The current records, walk starts and quadrics, into `mesh` and `start`.
    void download(Mesh& mesh, SimplifyStart& start) const;

private:
    VulkanContext& context_;
    SimplifyKernels kernels_;
    Buffer buffers_[kSimplifyBindingCount];
    SimplifyPush push_{};
};

// As simplifyParallel, with steps 1 to 3 of every round on the device.
ParallelSimplifyStats simplifyOnDevice(VulkanContext& context, Mesh& mesh, Image& values, uint32_t target);

}  // namespace ddt
