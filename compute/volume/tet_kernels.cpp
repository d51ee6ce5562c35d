#include "tet_kernels.h"

#include "commands.h"
#include "compute_pipeline.h"
#include "vulkan_error.h"

// SPIR-V written by glslangValidator at build time (see CMakeLists.txt).
#include "spirv/tet_apply.h"
#include "spirv/tet_candidates.h"
#include "spirv/tet_costs.h"
#include "spirv/tet_mark.h"
#include "spirv/tet_plan.h"
#include "spirv/tet_refresh.h"
#include "spirv/tet_scan.h"
#include "spirv/tet_select.h"

namespace ddt {

namespace {

// Texel buffers but for the control block and the indirect arguments, whole buffers.
std::vector<VkDescriptorType> tetBindingTypes() {
    std::vector<VkDescriptorType> types(kTetBindingCount, VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER);
    types[kTetBindingControl] = types[kTetBindingArgs] = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    return types;
}

}  // namespace

TetGroups tetGroupsFor(uint32_t count) {
    const uint32_t groups = (count + kTetGroupSize - 1) / kTetGroupSize;
    if (groups <= kTetMaxGroups) return {groups, 1};
    const uint32_t rows = (groups + kTetMaxGroups - 1) / kTetMaxGroups;
    return {(groups + rows - 1) / rows, rows};
}

TetKernels::TetKernels(VulkanContext& context) : layout_(context, tetBindingTypes(), sizeof(TetPush)) {
    plan_ = layout_.createKernel(kSpirvTetPlan, sizeof(kSpirvTetPlan));
    mark_ = layout_.createKernel(kSpirvTetMark, sizeof(kSpirvTetMark));
    candidates_ = layout_.createKernel(kSpirvTetCandidates, sizeof(kSpirvTetCandidates));
    select_ = layout_.createKernel(kSpirvTetSelect, sizeof(kSpirvTetSelect));
    scan_ = layout_.createKernel(kSpirvTetScan, sizeof(kSpirvTetScan));
    apply_ = layout_.createKernel(kSpirvTetApply, sizeof(kSpirvTetApply));
    refresh_ = layout_.createKernel(kSpirvTetRefresh, sizeof(kSpirvTetRefresh));
    costs_ = layout_.createKernel(kSpirvTetCosts, sizeof(kSpirvTetCosts));
}

void TetKernels::bind(const Buffer (&buffers)[kTetBindingCount]) { layout_.bind(buffers); }

VkPipeline TetKernels::kernelOf(uint32_t step) const {
    switch (step) {
        case kTetStepMark: return mark_;
        case kTetStepCandidates: return candidates_;
        case kTetStepClear:
        case kTetStepClaimHigh:
        case kTetStepClaimLow:
        case kTetStepCheck:
        case kTetStepTake:
        case kTetStepJudge: return select_;
        case kTetStepScan:
        case kTetStepUnmask: return scan_;
        case kTetStepApply: return apply_;
        case kTetStepRefresh: return refresh_;
        default: return costs_;
    }
}

void TetKernels::recordStep(VkCommandBuffer commands, TetPush push, const Buffer& args, VkQueryPool timestamps,
                            uint32_t query) const {
    layout_.bindKernel(commands, plan_, &push);
    vkCmdDispatch(commands, 1, 1, 1);
    computeBarrier(commands);
    layout_.bindKernel(commands, kernelOf(push.step), &push);
    vkCmdDispatchIndirect(commands, args.buffer, VkDeviceSize(push.step) * 16);
    computeBarrier(commands);
    if (timestamps) vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps, query);
}

void TetKernels::recordInit(VkCommandBuffer commands, TetPush push, uint32_t slots) const {
    push.step = kTetStepInit;
    const TetGroups groups = tetGroupsFor(slots);
    for (VkPipeline kernel : {refresh_, costs_}) {
        layout_.bindKernel(commands, kernel, &push);
        vkCmdDispatch(commands, groups.x, groups.y, 1);
        computeBarrier(commands);
    }
}

void TetKernels::recordTotals(VkCommandBuffer commands, TetPush push, uint32_t first) const {
    push.step = kTetStepTotals;
    push.first = first;
    const TetGroups groups = tetGroupsFor(kTetCostChunk);
    layout_.bindKernel(commands, costs_, &push);
    vkCmdDispatch(commands, groups.x, groups.y, 1);
    computeBarrier(commands);
}

}  // namespace ddt
