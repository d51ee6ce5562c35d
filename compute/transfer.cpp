#include "transfer.h"

#include <algorithm>
#include <cstring>

#include "commands.h"

namespace ddt {

namespace {

// Copies between a device-only buffer and the host through a staging buffer, in chunks.
const VkDeviceSize kStagingChunk = VkDeviceSize(32) << 20;

}  // namespace

// Only host-coherent memory is mapped, so no flush or invalidate is needed; every command
// batch ends with a barrier to the host (CommandBatch).
void uploadToBuffer(VulkanContext& context, Buffer& buffer, const void* data, VkDeviceSize size) {
    if (buffer.mapped) {
        std::memcpy(buffer.mapped, data, size);
        return;
    }
    Buffer staging = createBuffer(context, std::min(size, kStagingChunk), Placement::Readback);
    for (VkDeviceSize offset = 0; offset < size; offset += kStagingChunk) {
        const VkDeviceSize chunk = std::min(kStagingChunk, size - offset);
        std::memcpy(staging.mapped, static_cast<const char*>(data) + offset, chunk);
        CommandBatch commands(context);
        VkBufferCopy region{0, offset, chunk};
        vkCmdCopyBuffer(commands.buffer(), staging.buffer, buffer.buffer, 1, &region);
        commands.submitAndWait();
    }
    destroyBuffer(context, staging);
}

void downloadFromBuffer(VulkanContext& context, const Buffer& buffer, void* data, VkDeviceSize size,
                        VkDeviceSize offset) {
    if (buffer.mapped) {
        std::memcpy(data, static_cast<const char*>(buffer.mapped) + offset, size);
        return;
    }
    Buffer staging = createBuffer(context, std::min(size, kStagingChunk), Placement::Readback);
    for (VkDeviceSize done = 0; done < size; done += kStagingChunk) {
        const VkDeviceSize chunk = std::min(kStagingChunk, size - done);
        CommandBatch commands(context);
        VkBufferCopy region{offset + done, 0, chunk};
        vkCmdCopyBuffer(commands.buffer(), buffer.buffer, staging.buffer, 1, &region);
        commands.submitAndWait();
        std::memcpy(static_cast<char*>(data) + done, staging.mapped, chunk);
    }
    destroyBuffer(context, staging);
}

}  // namespace ddt
