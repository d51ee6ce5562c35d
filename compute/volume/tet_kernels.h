// The tetrahedral flip kernels (glsl/volume/) with their own pipeline layout (the bindings of
// glsl/volume/tet_layout.h and TetPush) and one descriptor set (compute/kernel_layout.h).
#pragma once

#include <vulkan/vulkan.h>

#include "buffer.h"
#include "context.h"
#include "kernel_layout.h"
#include "volume/tet_layout.h"

namespace ddt {

class TetKernels {
public:
    explicit TetKernels(VulkanContext& context);
    TetKernels(const TetKernels&) = delete;
    TetKernels& operator=(const TetKernels&) = delete;

    // Points binding i at buffers[i], for every binding.
    void bind(const Buffer (&buffers)[kTetBindingCount]);
    // One step of a round: tet_plan.comp sizes the step's indirect dispatch (from `args`), then
    // the step's kernel runs; each followed by the compute barrier.
    // With `timestamps`, writes timestamp `query` after the step.
    void recordStep(VkCommandBuffer commands, TetPush push, const Buffer& args, VkQueryPool timestamps = VK_NULL_HANDLE,
                    uint32_t query = 0) const;
    // The first round's cache: tet_refresh, then tet_costs, over `slots` slots (kTetStepInit).
    void recordInit(VkCommandBuffer commands, TetPush push, uint32_t slots) const;
    // tet_costs' chunk of costs from slot `first` (kTetStepTotals, the variance weight).
    void recordTotals(VkCommandBuffer commands, TetPush push, uint32_t first) const;

private:
    VkPipeline kernelOf(uint32_t step) const;

    KernelLayout layout_;  // makes the kernels below, and destroys them with it
    VkPipeline plan_ = VK_NULL_HANDLE;        // tet_plan.comp
    VkPipeline mark_ = VK_NULL_HANDLE;        // tet_mark.comp
    VkPipeline candidates_ = VK_NULL_HANDLE;  // tet_candidates.comp
    VkPipeline select_ = VK_NULL_HANDLE;      // tet_select.comp
    VkPipeline scan_ = VK_NULL_HANDLE;        // tet_scan.comp
    VkPipeline apply_ = VK_NULL_HANDLE;       // tet_apply.comp
    VkPipeline refresh_ = VK_NULL_HANDLE;     // tet_refresh.comp
    VkPipeline costs_ = VK_NULL_HANDLE;       // tet_costs.comp
};

// Workgroups of kTetGroupSize for `count` items: (x, y), y > 1 only beyond kTetMaxGroups groups
// (as tet_plan.comp's setArgs).
struct TetGroups {
    uint32_t x, y;
};
TetGroups tetGroupsFor(uint32_t count);

}  // namespace ddt
