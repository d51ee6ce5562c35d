// Device buffers, optionally with a texel view (the kernels' arrays); transfer.h moves data
// between them and the host.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>

#include "context.h"

namespace ddt {

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkBufferView view = VK_NULL_HANDLE;  // storage texel view, when created with a format
    VkDeviceSize size = 0;
    void* mapped = nullptr;  // set when the memory is host-visible
};

enum class Placement {
    Device,    // device-local (mapped too where the device allows)
    Readback,  // host-visible and cached, for results the host reads
};

// Every buffer may be a storage buffer, a storage texel buffer, an indirect-argument buffer
// and a transfer source or destination. With a format, it gets a storage texel view.
Buffer createBuffer(VulkanContext& context, VkDeviceSize size, Placement placement = Placement::Device,
                    VkFormat view_format = VK_FORMAT_UNDEFINED);
void destroyBuffer(VulkanContext& context, Buffer& buffer);

// The largest device memory one createBuffer has taken so far in this process (0: none), for --stats.
uint64_t largestDeviceBuffer();

}  // namespace ddt
