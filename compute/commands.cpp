#include "commands.h"

#include "vulkan_error.h"

namespace ddt {

void computeBarrier(VkCommandBuffer commands) {
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                            VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT |
                            VK_ACCESS_TRANSFER_WRITE_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT |
                             VK_PIPELINE_STAGE_TRANSFER_BIT,
                         0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void hostBarrier(VkCommandBuffer commands) {
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

namespace {

void bind(VkCommandBuffer commands, VkPipeline kernel, const KernelBindings& bindings, const PushConstants& push) {
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, kernel);
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, bindings.layout, 0, 1, &bindings.set, 0, nullptr);
    vkCmdPushConstants(commands, bindings.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
}

}  // namespace

void dispatch(VkCommandBuffer commands, VkPipeline kernel, const KernelBindings& bindings, const PushConstants& push,
              uint32_t groups) {
    bind(commands, kernel, bindings, push);
    vkCmdDispatch(commands, groups, 1, 1);
    computeBarrier(commands);
}

void dispatch2D(VkCommandBuffer commands, VkPipeline kernel, const KernelBindings& bindings, const PushConstants& push,
                uint32_t groups_x, uint32_t groups_y) {
    bind(commands, kernel, bindings, push);
    vkCmdDispatch(commands, groups_x, groups_y, 1);
    computeBarrier(commands);
}

void dispatchIndirect(VkCommandBuffer commands, VkPipeline kernel, const KernelBindings& bindings,
                      const PushConstants& push, const Buffer& args, uint32_t slot) {
    bind(commands, kernel, bindings, push);
    // Slots are uvec3 in a std430 array: 16 bytes apart.
    vkCmdDispatchIndirect(commands, args.buffer, VkDeviceSize(slot) * 16);
    computeBarrier(commands);
}

CommandBatch::CommandBatch(VulkanContext& context) : context_(context) {
    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate.commandPool = context.command_pool;
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    VK_CHECK(vkAllocateCommandBuffers(context.device, &allocate, &buffer_));
    VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(context.device, &fence, nullptr, &fence_));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    VK_CHECK(vkBeginCommandBuffer(buffer_, &begin));
}

CommandBatch::~CommandBatch() {
    vkDestroyFence(context_.device, fence_, nullptr);
    vkFreeCommandBuffers(context_.device, context_.command_pool, 1, &buffer_);
}

void CommandBatch::finishRecording() {
    if (!recording_) return;
    hostBarrier(buffer_);
    VK_CHECK(vkEndCommandBuffer(buffer_));
    recording_ = false;
}

void CommandBatch::submitAndWait() {
    finishRecording();
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &buffer_;
    VK_CHECK(vkQueueSubmit(context_.queue, 1, &submit, fence_));
    VK_CHECK(vkWaitForFences(context_.device, 1, &fence_, VK_TRUE, UINT64_MAX));
    VK_CHECK(vkResetFences(context_.device, 1, &fence_));
}

}  // namespace ddt
