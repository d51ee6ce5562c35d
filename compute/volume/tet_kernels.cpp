#include "tet_kernels.h"

#include "commands.h"
#include "kernels.h"
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

VkDescriptorType tetBindingType(uint32_t binding) {
    return binding == kTetBindingControl || binding == kTetBindingArgs ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                                                                       : VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
}

}  // namespace

TetGroups tetGroupsFor(uint32_t count) {
    const uint32_t groups = (count + kTetGroupSize - 1) / kTetGroupSize;
    if (groups <= kTetMaxGroups) return {groups, 1};
    const uint32_t rows = (groups + kTetMaxGroups - 1) / kTetMaxGroups;
    return {(groups + rows - 1) / rows, rows};
}

TetKernels::TetKernels(VulkanContext& context) : context_(context) {
    try {
        VkDescriptorSetLayoutBinding bindings[kTetBindingCount];
        for (uint32_t i = 0; i < kTetBindingCount; ++i)
            bindings[i] = {i, tetBindingType(i), 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
        VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        set_info.bindingCount = kTetBindingCount;
        set_info.pBindings = bindings;
        VK_CHECK(vkCreateDescriptorSetLayout(context.device, &set_info, nullptr, &set_layout_));
        VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(TetPush)};
        VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        layout_info.setLayoutCount = 1;
        layout_info.pSetLayouts = &set_layout_;
        layout_info.pushConstantRangeCount = 1;
        layout_info.pPushConstantRanges = &range;
        VK_CHECK(vkCreatePipelineLayout(context.device, &layout_info, nullptr, &layout_));
        plan_ = createComputePipeline(context, layout_, kSpirvTetPlan, sizeof(kSpirvTetPlan));
        mark_ = createComputePipeline(context, layout_, kSpirvTetMark, sizeof(kSpirvTetMark));
        candidates_ = createComputePipeline(context, layout_, kSpirvTetCandidates, sizeof(kSpirvTetCandidates));
        select_ = createComputePipeline(context, layout_, kSpirvTetSelect, sizeof(kSpirvTetSelect));
        scan_ = createComputePipeline(context, layout_, kSpirvTetScan, sizeof(kSpirvTetScan));
        apply_ = createComputePipeline(context, layout_, kSpirvTetApply, sizeof(kSpirvTetApply));
        refresh_ = createComputePipeline(context, layout_, kSpirvTetRefresh, sizeof(kSpirvTetRefresh));
        costs_ = createComputePipeline(context, layout_, kSpirvTetCosts, sizeof(kSpirvTetCosts));
        const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, kTetBindingCount - 2},
                                              {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2}};
        VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pool_info.maxSets = 1;
        pool_info.poolSizeCount = 2;
        pool_info.pPoolSizes = sizes;
        VK_CHECK(vkCreateDescriptorPool(context.device, &pool_info, nullptr, &pool_));
        VkDescriptorSetAllocateInfo allocate{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        allocate.descriptorPool = pool_;
        allocate.descriptorSetCount = 1;
        allocate.pSetLayouts = &set_layout_;
        VK_CHECK(vkAllocateDescriptorSets(context.device, &allocate, &set_));
    } catch (...) {
        destroy();
        throw;
    }
}

TetKernels::~TetKernels() { destroy(); }

void TetKernels::destroy() {
    const VkDevice device = context_.device;
    if (pool_) vkDestroyDescriptorPool(device, pool_, nullptr);
    for (VkPipeline* pipeline : {&plan_, &mark_, &candidates_, &select_, &scan_, &apply_, &refresh_, &costs_}) {
        if (*pipeline) vkDestroyPipeline(device, *pipeline, nullptr);
        *pipeline = VK_NULL_HANDLE;
    }
    if (layout_) vkDestroyPipelineLayout(device, layout_, nullptr);
    if (set_layout_) vkDestroyDescriptorSetLayout(device, set_layout_, nullptr);
    pool_ = VK_NULL_HANDLE;
    layout_ = VK_NULL_HANDLE;
    set_layout_ = VK_NULL_HANDLE;
}

void TetKernels::bind(const Buffer (&buffers)[kTetBindingCount]) {
    VkWriteDescriptorSet writes[kTetBindingCount];
    VkDescriptorBufferInfo infos[kTetBindingCount];
    for (uint32_t i = 0; i < kTetBindingCount; ++i) {
        writes[i] = descriptorWrite(set_, i, tetBindingType(i));
        if (tetBindingType(i) == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) {
            infos[i] = {buffers[i].buffer, 0, VK_WHOLE_SIZE};
            writes[i].pBufferInfo = &infos[i];
        } else {
            writes[i].pTexelBufferView = &buffers[i].view;
        }
    }
    vkUpdateDescriptorSets(context_.device, kTetBindingCount, writes, 0, nullptr);
}

VkPipeline TetKernels::kernelOf(uint32_t step) const {
    switch (step) {
        case kTetStepMark: return mark_;
        case kTetStepCandidates: return candidates_;
        case kTetStepClaimHigh:
        case kTetStepClaimLow:
        case kTetStepCheck:
        case kTetStepTake:
        case kTetStepJudge:
        case kTetStepClear: return select_;
        case kTetStepScan:
        case kTetStepUnmask: return scan_;
        case kTetStepApply: return apply_;
        case kTetStepRefresh: return refresh_;
        default: return costs_;
    }
}

void TetKernels::bindKernel(VkCommandBuffer commands, VkPipeline kernel, const TetPush& push) const {
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, kernel);
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
    vkCmdPushConstants(commands, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
}

void TetKernels::recordStep(VkCommandBuffer commands, TetPush push, const Buffer& args, VkQueryPool timestamps,
                            uint32_t query) const {
    bindKernel(commands, plan_, push);
    vkCmdDispatch(commands, 1, 1, 1);
    computeBarrier(commands);
    bindKernel(commands, kernelOf(push.step), push);
    vkCmdDispatchIndirect(commands, args.buffer, VkDeviceSize(push.step) * 16);
    computeBarrier(commands);
    if (timestamps) vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps, query);
}

void TetKernels::recordInit(VkCommandBuffer commands, TetPush push, uint32_t slots) const {
    push.step = kTetStepInit;
    const TetGroups groups = tetGroupsFor(slots);
    for (VkPipeline kernel : {refresh_, costs_}) {
        bindKernel(commands, kernel, push);
        vkCmdDispatch(commands, groups.x, groups.y, 1);
        computeBarrier(commands);
    }
}

}  // namespace ddt
