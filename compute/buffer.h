// Storage buffers reached by device address, and transfers between them and the host.
// On devices whose device-local memory is host-visible (lavapipe, integrated GPUs) buffers
// are mapped and transfers are plain copies; otherwise they go through a staging buffer.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>

#include "context.h"

namespace ddt {

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    VkDeviceAddress address = 0;
    void* mapped = nullptr;  // set when the memory is host-visible
};

enum class Placement {
    Device,    // device-local (mapped too where the device allows)
    Readback,  // host-visible and cached, for results the host reads
};

// Every buffer may be a storage buffer (by address), an indirect-argument buffer and a
// transfer source or destination.
Buffer createBuffer(VulkanContext& context, VkDeviceSize size, Placement placement = Placement::Device);
void destroyBuffer(VulkanContext& context, Buffer& buffer);

void uploadToBuffer(VulkanContext& context, Buffer& buffer, const void* data, VkDeviceSize size);
void downloadFromBuffer(VulkanContext& context, const Buffer& buffer, void* data, VkDeviceSize size,
                        VkDeviceSize offset = 0);

}  // namespace ddt
