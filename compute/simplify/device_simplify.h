// The parallel simplification rule (core/simplify/parallel_simplify.h) on a Vulkan device, in
// kernels of its own (glsl/simplify/). So far a round's first two steps, equal to core's bit
// for bit: every edge's best legal collapse (the legality walks, the exact orientation and the
// quadric's value are the same formulas, in fp64 without fused multiply-add, and the key is a
// cut of the cost, not a rounding), then the winners, whose regions hold no smaller key; and
// step 3, the chosen winners' collapses and quadric merges. Choosing the least winners on the
// device, keeping candidates of unchanged regions and the loop over rounds are to follow.
#pragma once

#include <vector>

#include "context.h"
#include "image.h"
#include "parallel_simplify.h"

namespace ddt {

struct DeviceRoundSelection {
    std::vector<CollapseCandidate> candidates;  // per edge
    std::vector<uint32_t> winners;              // ascending
};

// Step 3 for `collapses` (winners of one selection, in any order): afterwards the mesh, its walks'
// starts and quadrics in `start` are as core's collapseEdge and quadric merge leave them.
void deviceCollapse(VulkanContext& context, Mesh& mesh, SimplifyStart& start, const Image& values,
                    const std::vector<Collapse>& collapses);

// Steps 1 and 2 of a round for the mesh, its walks' starts and quadrics in `start`, and the
// vertex values `values` (what start.points reads).
DeviceRoundSelection deviceSelectCollapses(VulkanContext& context, const Mesh& mesh, const SimplifyStart& start,
                                           const Image& values);

}  // namespace ddt
