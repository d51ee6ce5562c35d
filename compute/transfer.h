// Transfers between device buffers and the host. On devices whose device-local memory is
// host-visible (lavapipe, integrated GPUs) buffers are mapped and transfers are plain copies;
// otherwise they go through a staging buffer, copied by a command batch (commands.h).
#pragma once

#include <vulkan/vulkan.h>

#include "buffer.h"
#include "context.h"

namespace ddt {

void uploadToBuffer(VulkanContext& context, Buffer& buffer, const void* data, VkDeviceSize size);
void downloadFromBuffer(VulkanContext& context, const Buffer& buffer, void* data, VkDeviceSize size,
                        VkDeviceSize offset = 0);

}  // namespace ddt
