// What every capability's kernels are made with: a compute pipeline from embedded SPIR-V,
// and descriptor writes for the buffers they bind.
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>

#include "context.h"

namespace ddt {

// A write of one descriptor of `type` at `binding` of `set`; the caller points it at its buffer.
VkWriteDescriptorSet descriptorWrite(VkDescriptorSet set, uint32_t binding, VkDescriptorType type);

// A compute pipeline of `bytes` of SPIR-V with `layout` (for kernels with layouts of their own).
VkPipeline createComputePipeline(VulkanContext& context, VkPipelineLayout layout, const uint32_t* spirv, size_t bytes,
                                 const VkSpecializationInfo* specialization = nullptr);

}  // namespace ddt
