#include "compute_pipeline.h"

#include "vulkan_error.h"

namespace ddt {

VkWriteDescriptorSet descriptorWrite(VkDescriptorSet set, uint32_t binding, VkDescriptorType type) {
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.dstBinding = binding;
    write.descriptorCount = 1;
    write.descriptorType = type;
    return write;
}

VkPipeline createComputePipeline(VulkanContext& context, VkPipelineLayout layout, const uint32_t* spirv, size_t bytes,
                                 const VkSpecializationInfo* specialization) {
    VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    module_info.codeSize = bytes;
    module_info.pCode = spirv;
    VkShaderModule module;
    VK_CHECK(vkCreateShaderModule(context.device, &module_info, nullptr, &module));
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = specialization;
    info.layout = layout;
    VkPipeline pipeline;
    VkResult result = vkCreateComputePipelines(context.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
    vkDestroyShaderModule(context.device, module, nullptr);
    VK_CHECK(result);
    return pipeline;
}

}  // namespace ddt
