#include "kernel_layout.h"

#include "compute_pipeline.h"
#include "vulkan_error.h"

namespace ddt {

KernelLayout::KernelLayout(VulkanContext& context, std::vector<VkDescriptorType> bindings, uint32_t push_bytes)
    : context_(context), bindings_(std::move(bindings)), push_bytes_(push_bytes) {
    try {
        const uint32_t count = uint32_t(bindings_.size());
        std::vector<VkDescriptorSetLayoutBinding> layout_bindings(count);
        uint32_t texel = 0;
        for (uint32_t i = 0; i < count; ++i) {
            layout_bindings[i] = {i, bindings_[i], 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
            texel += bindings_[i] == VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
        }
        VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        set_info.bindingCount = count;
        set_info.pBindings = layout_bindings.data();
        VK_CHECK(vkCreateDescriptorSetLayout(context.device, &set_info, nullptr, &set_layout_));
        VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes_};
        VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        layout_info.setLayoutCount = 1;
        layout_info.pSetLayouts = &set_layout_;
        layout_info.pushConstantRangeCount = 1;
        layout_info.pPushConstantRanges = &range;
        VK_CHECK(vkCreatePipelineLayout(context.device, &layout_info, nullptr, &layout_));
        std::vector<VkDescriptorPoolSize> sizes;
        if (texel) sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, texel});
        if (count > texel) sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, count - texel});
        VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pool_info.maxSets = 1;
        pool_info.poolSizeCount = uint32_t(sizes.size());
        pool_info.pPoolSizes = sizes.data();
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

KernelLayout::~KernelLayout() { destroy(); }

void KernelLayout::destroy() {
    const VkDevice device = context_.device;
    for (VkPipeline kernel : kernels_) vkDestroyPipeline(device, kernel, nullptr);
    kernels_.clear();
    if (pool_) vkDestroyDescriptorPool(device, pool_, nullptr);
    if (layout_) vkDestroyPipelineLayout(device, layout_, nullptr);
    if (set_layout_) vkDestroyDescriptorSetLayout(device, set_layout_, nullptr);
    pool_ = VK_NULL_HANDLE;
    layout_ = VK_NULL_HANDLE;
    set_layout_ = VK_NULL_HANDLE;
}

VkPipeline KernelLayout::createKernel(const uint32_t* spirv, size_t bytes) {
    kernels_.push_back(createComputePipeline(context_, layout_, spirv, bytes));
    return kernels_.back();
}

void KernelLayout::bind(const Buffer* buffers) {
    const uint32_t count = uint32_t(bindings_.size());
    std::vector<VkWriteDescriptorSet> writes(count);
    std::vector<VkDescriptorBufferInfo> infos(count);
    for (uint32_t i = 0; i < count; ++i) {
        writes[i] = descriptorWrite(set_, i, bindings_[i]);
        if (bindings_[i] == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) {
            infos[i] = {buffers[i].buffer, 0, VK_WHOLE_SIZE};
            writes[i].pBufferInfo = &infos[i];
        } else {
            writes[i].pTexelBufferView = &buffers[i].view;
        }
    }
    vkUpdateDescriptorSets(context_.device, count, writes.data(), 0, nullptr);
}

void KernelLayout::bindKernel(VkCommandBuffer commands, VkPipeline kernel, const void* push) const {
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, kernel);
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
    vkCmdPushConstants(commands, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes_, push);
}

}  // namespace ddt
