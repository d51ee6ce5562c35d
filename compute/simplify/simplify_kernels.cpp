#include "simplify_kernels.h"

#include <algorithm>

#include "commands.h"
#include "kernels.h"
#include "layout.h"
#include "vulkan_error.h"

// SPIR-V written by glslangValidator at build time (see CMakeLists.txt).
#include "spirv/collapse_candidates.h"
#include "spirv/collapse_edges.h"
#include "spirv/gather_edges.h"
#include "spirv/select_collapses.h"

namespace ddt {

SimplifyKernels::SimplifyKernels(VulkanContext& context) : context_(context) {
    try {
        VkDescriptorSetLayoutBinding bindings[kSimplifyBindingCount];
        for (uint32_t i = 0; i < kSimplifyBindingCount; ++i)
            bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
        VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        set_info.bindingCount = kSimplifyBindingCount;
        set_info.pBindings = bindings;
        VK_CHECK(vkCreateDescriptorSetLayout(context.device, &set_info, nullptr, &set_layout_));
        VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(SimplifyPush)};
        VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        layout_info.setLayoutCount = 1;
        layout_info.pSetLayouts = &set_layout_;
        layout_info.pushConstantRangeCount = 1;
        layout_info.pPushConstantRanges = &range;
        VK_CHECK(vkCreatePipelineLayout(context.device, &layout_info, nullptr, &layout_));
        gather = createComputePipeline(context, layout_, kSpirvGatherEdges, sizeof(kSpirvGatherEdges));
        candidates = createComputePipeline(context, layout_, kSpirvCollapseCandidates, sizeof(kSpirvCollapseCandidates));
        select = createComputePipeline(context, layout_, kSpirvSelectCollapses, sizeof(kSpirvSelectCollapses));
        collapse = createComputePipeline(context, layout_, kSpirvCollapseEdges, sizeof(kSpirvCollapseEdges));
        VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, kSimplifyBindingCount};
        VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pool_info.maxSets = 1;
        pool_info.poolSizeCount = 1;
        pool_info.pPoolSizes = &size;
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

SimplifyKernels::~SimplifyKernels() { destroy(); }

void SimplifyKernels::destroy() {
    const VkDevice device = context_.device;
    if (pool_) vkDestroyDescriptorPool(device, pool_, nullptr);
    for (VkPipeline pipeline : {gather, candidates, select, collapse})
        if (pipeline) vkDestroyPipeline(device, pipeline, nullptr);
    if (layout_) vkDestroyPipelineLayout(device, layout_, nullptr);
    if (set_layout_) vkDestroyDescriptorSetLayout(device, set_layout_, nullptr);
    pool_ = VK_NULL_HANDLE;
    gather = candidates = select = collapse = VK_NULL_HANDLE;
    layout_ = VK_NULL_HANDLE;
    set_layout_ = VK_NULL_HANDLE;
}

void SimplifyKernels::bind(const Buffer (&buffers)[kSimplifyBindingCount]) {
    VkWriteDescriptorSet writes[kSimplifyBindingCount];
    for (uint32_t i = 0; i < kSimplifyBindingCount; ++i) {
        writes[i] = descriptorWrite(set_, i, VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER);
        writes[i].pTexelBufferView = &buffers[i].view;
    }
    vkUpdateDescriptorSets(context_.device, kSimplifyBindingCount, writes, 0, nullptr);
}

void SimplifyKernels::dispatchPerEdge(VkCommandBuffer commands, VkPipeline kernel, SimplifyPush push) const {
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, kernel);
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
    const uint32_t per_dispatch = kMaxGroups * kGroupSize;
    for (uint32_t first = 0; first < push.edge_count; first += per_dispatch) {
        push.first_edge = first;
        vkCmdPushConstants(commands, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
        vkCmdDispatch(commands, (std::min(per_dispatch, push.edge_count - first) + kGroupSize - 1) / kGroupSize, 1, 1);
        computeBarrier(commands);
    }
}

}  // namespace ddt
