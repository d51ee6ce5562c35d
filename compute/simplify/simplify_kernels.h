// The simplification kernels (glsl/simplify/) with their own pipeline layout (the bindings of
// glsl/simplify/simplify_layout.h and SimplifyPush) and one descriptor set (compute/kernel_layout.h).
#pragma once

#include <vulkan/vulkan.h>

#include "buffer.h"
#include "context.h"
#include "kernel_layout.h"
#include "simplify/simplify_layout.h"

namespace ddt {

class SimplifyKernels {
public:
    explicit SimplifyKernels(VulkanContext& context);
    SimplifyKernels(const SimplifyKernels&) = delete;
    SimplifyKernels& operator=(const SimplifyKernels&) = delete;

    // Points binding i at buffers[i], for every binding.
    void bind(const Buffer (&buffers)[kSimplifyBindingCount]);
    // Records `kernel` with one invocation an edge (or listed edge, or collapse) of
    // push.edge_count, in as many dispatches of kMaxGroups groups as that needs, each followed
    // by the compute barrier.
    void dispatchPerEdge(VkCommandBuffer commands, VkPipeline kernel, SimplifyPush push) const;

    VkPipeline gather = VK_NULL_HANDLE;      // gather_edges.comp
    VkPipeline candidates = VK_NULL_HANDLE;  // collapse_candidates.comp
    VkPipeline select = VK_NULL_HANDLE;      // select_collapses.comp
    VkPipeline collapse = VK_NULL_HANDLE;    // collapse_edges.comp

private:
    KernelLayout layout_;  // makes the kernels above, and destroys them with it
};

}  // namespace ddt
