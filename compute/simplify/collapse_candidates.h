// The parallel simplification rule (core/simplify/parallel_simplify.h) on a Vulkan device, in
// kernels of its own (glsl/simplify/, bindings in simplify_layout.h). So far its step 1:
// every edge's best legal collapse, equal to core's bestCollapse bit for bit (the legality
// walks, the exact orientation and the quadric's value are the same formulas, in fp64 without
// fused multiply-add, and the key is a cut of the cost, not a rounding). The selection and the
// collapses themselves are to follow.
#pragma once

#include <vector>

#include "context.h"
#include "image.h"
#include "parallel_simplify.h"

namespace ddt {

// Every edge's candidate for the mesh, its walks' starts and quadrics in `start`, and the
// vertex values `values` (what start.points reads). One invocation an edge.
std::vector<CollapseCandidate> deviceCollapseCandidates(VulkanContext& context, const Mesh& mesh,
                                                        const SimplifyStart& start, const Image& values);

}  // namespace ddt
