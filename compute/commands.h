// Recording and submitting compute work. A pass is: bind the kernel and its bindings, push
// constants, dispatch (directly or from indirect arguments), then the one barrier every
// pass ends with.
#pragma once

#include <vulkan/vulkan.h>

#include "buffer.h"
#include "context.h"
#include "layout.h"

namespace ddt {

// The barrier after every dispatch: all shader writes become visible to later shader reads
// and writes, to indirect-argument reads and to transfers. Every kernel step depends on the
// one before, so one global barrier is both simplest and exact.
void computeBarrier(VkCommandBuffer commands);

// Makes shader and transfer writes visible to the host before it reads mapped memory.
void hostBarrier(VkCommandBuffer commands);

// What every dispatch binds: the shared pipeline layout and the job's descriptor set.
struct KernelBindings {
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
};

void dispatch(VkCommandBuffer commands, VkPipeline kernel, const KernelBindings& bindings, const PushConstants& push,
              uint32_t groups);
void dispatch2D(VkCommandBuffer commands, VkPipeline kernel, const KernelBindings& bindings, const PushConstants& push,
                uint32_t groups_x, uint32_t groups_y);
void dispatchIndirect(VkCommandBuffer commands, VkPipeline kernel, const KernelBindings& bindings,
                      const PushConstants& push, const Buffer& args, uint32_t slot);

// A primary command buffer recorded once and submitted (possibly many times), waiting on a
// fence each time. Recording ends with a barrier to the host, so after the wait the host
// may read what the commands wrote.
class CommandBatch {
public:
    explicit CommandBatch(VulkanContext& context);
    ~CommandBatch();
    CommandBatch(const CommandBatch&) = delete;
    CommandBatch& operator=(const CommandBatch&) = delete;

    VkCommandBuffer buffer() const { return buffer_; }
    void finishRecording();
    void submitAndWait();

private:
    VulkanContext& context_;
    VkCommandBuffer buffer_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    bool recording_ = true;
};

}  // namespace ddt
