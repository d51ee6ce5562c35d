#include "buffer.h"

#include <algorithm>
#include <cstdlib>

#include "largest_size.h"
#include "vulkan_error.h"

namespace ddt {

namespace {

constinit LargestSize device_buffers;

uint32_t findMemoryType(const VulkanContext& context, uint32_t allowed, Placement placement) {
    const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    // Preferences in order; the first type that matches one wins.
    const VkMemoryPropertyFlags device_wanted[] = {VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0};
    const VkMemoryPropertyFlags readback_wanted[] = {host | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, host};
    const VkMemoryPropertyFlags* wanted = placement == Placement::Device ? device_wanted : readback_wanted;
    for (int preference = 0; preference < 2; ++preference) {
        for (uint32_t i = 0; i < context.memory.memoryTypeCount; ++i) {
            const VkMemoryPropertyFlags flags = context.memory.memoryTypes[i].propertyFlags;
            if ((allowed & (1u << i)) && (flags & wanted[preference]) == wanted[preference]) return i;
        }
    }
    throw UserError("Vulkan: no suitable memory type on " + context.info.name);
}

// Test hook: with DDTUP_TEST_DEVICE_MEMORY=bytes set, allocations larger than that fail as if
// the device were out of memory, which tests cannot provoke for real. Read at every
// allocation, so a test can lift it and check that the backend recovers.
VkDeviceSize testAllocationLimit() {
    const char* limit = std::getenv("DDTUP_TEST_DEVICE_MEMORY");
    return limit && *limit ? std::strtoull(limit, nullptr, 10) : ~VkDeviceSize(0);
}

}  // namespace

Buffer createBuffer(VulkanContext& context, VkDeviceSize size, Placement placement, VkFormat view_format) {
    Buffer buffer;
    buffer.size = size;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = std::max<VkDeviceSize>(size, 16);
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT |
                 VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                 VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VK_CHECK(vkCreateBuffer(context.device, &info, nullptr, &buffer.buffer));

    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(context.device, buffer.buffer, &requirements);
    const uint32_t type = findMemoryType(context, requirements.memoryTypeBits, placement);
    VkMemoryAllocateInfo allocate{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocate.allocationSize = requirements.size;
    allocate.memoryTypeIndex = type;
    VkResult result = requirements.size > testAllocationLimit()
                          ? VK_ERROR_OUT_OF_DEVICE_MEMORY
                          : vkAllocateMemory(context.device, &allocate, nullptr, &buffer.memory);
    if (result != VK_SUCCESS) {
        vkDestroyBuffer(context.device, buffer.buffer, nullptr);
        checkVulkan(result, "vkAllocateMemory");
    }
    VK_CHECK(vkBindBufferMemory(context.device, buffer.buffer, buffer.memory, 0));
    device_buffers.note(requirements.size);
    const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    if ((context.memory.memoryTypes[type].propertyFlags & host) == host)
        VK_CHECK(vkMapMemory(context.device, buffer.memory, 0, VK_WHOLE_SIZE, 0, &buffer.mapped));
    if (view_format != VK_FORMAT_UNDEFINED) {
        VkBufferViewCreateInfo view{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
        view.buffer = buffer.buffer;
        view.format = view_format;
        view.range = VK_WHOLE_SIZE;
        VK_CHECK(vkCreateBufferView(context.device, &view, nullptr, &buffer.view));
    }
    return buffer;
}

uint64_t largestDeviceBuffer() { return device_buffers.largest(); }

void destroyBuffer(VulkanContext& context, Buffer& buffer) {
    if (buffer.view) vkDestroyBufferView(context.device, buffer.view, nullptr);
    if (buffer.buffer) vkDestroyBuffer(context.device, buffer.buffer, nullptr);
    if (buffer.memory) vkFreeMemory(context.device, buffer.memory, nullptr);
    buffer = Buffer{};
}

}  // namespace ddt
