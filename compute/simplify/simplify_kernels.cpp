#include "simplify_kernels.h"

#include "compute_pipeline.h"
#include "layout.h"
#include "vulkan_error.h"

// SPIR-V written by glslangValidator at build time (see CMakeLists.txt).
#include "spirv/collapse_candidates.h"
#include "spirv/collapse_edges.h"
#include "spirv/gather_edges.h"
#include "spirv/select_collapses.h"

namespace ddt {

SimplifyKernels::SimplifyKernels(VulkanContext& context)
    : layout_(context, std::vector<VkDescriptorType>(kSimplifyBindingCount, VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER),
              sizeof(SimplifyPush)) {
    gather = layout_.createKernel(kSpirvGatherEdges, sizeof(kSpirvGatherEdges));
    candidates = layout_.createKernel(kSpirvCollapseCandidates, sizeof(kSpirvCollapseCandidates));
    select = layout_.createKernel(kSpirvSelectCollapses, sizeof(kSpirvSelectCollapses));
    collapse = layout_.createKernel(kSpirvCollapseEdges, sizeof(kSpirvCollapseEdges));
}

void SimplifyKernels::bind(const Buffer (&buffers)[kSimplifyBindingCount]) { layout_.bind(buffers); }

void SimplifyKernels::dispatchPerEdge(VkCommandBuffer commands, VkPipeline kernel, SimplifyPush push) const {
    layout_.dispatchPerEdge(commands, kernel, push);
}

}  // namespace ddt
