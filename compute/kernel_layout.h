// The Vulkan objects a family of compute kernels shares: one descriptor set of storage buffers
// (texel buffers, or whole buffers for the few that atomics or indirect arguments need), one
// push-constant range, one pipeline layout, and the kernels' pipelines, all destroyed with it.
// The simplification's kernels and the tetrahedral flips' are such families.
#pragma once

#include <vulkan/vulkan.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "buffer.h"
#include "commands.h"
#include "context.h"

namespace ddt {

class KernelLayout {
public:
    // bindings[i]: binding i's type (storage texel buffer or storage buffer).
    KernelLayout(VulkanContext& context, std::vector<VkDescriptorType> bindings, uint32_t push_bytes);
    ~KernelLayout();
    KernelLayout(const KernelLayout&) = delete;
    KernelLayout& operator=(const KernelLayout&) = delete;

    // A kernel from embedded SPIR-V with this layout; destroyed with the layout.
    VkPipeline createKernel(const uint32_t* spirv, size_t bytes);
    // Points binding i at buffers[i] (its texel view or the whole buffer, by the binding's type),
    // for every binding.
    void bind(const Buffer* buffers);
    // Binds `kernel`, the set and `push` (push_bytes of it) for the dispatches that follow.
    void bindKernel(VkCommandBuffer commands, VkPipeline kernel, const void* push) const;
    // Records `kernel` with one invocation an edge for push.edge_count edges, in as many
    // dispatches of kMaxGroups groups as that needs (push.first_edge: each one's first edge),
    // each followed by the compute barrier. With `args`, each dispatch's group count is read on
    // the device from its slot, first_slot, first_slot + 1, … (VkDispatchIndirectCommand, 16
    // bytes apart), which an earlier kernel wrote.
    template <typename Push>
    void dispatchPerEdge(VkCommandBuffer commands, VkPipeline kernel, Push push, const Buffer* args = nullptr,
                         uint32_t first_slot = 0) const {
        const uint32_t per_dispatch = kMaxGroups * kGroupSize;
        uint32_t slot = first_slot;
        for (uint32_t first = 0; first < push.edge_count; first += per_dispatch, ++slot) {
            push.first_edge = first;
            bindKernel(commands, kernel, &push);
            if (args)
                vkCmdDispatchIndirect(commands, args->buffer, VkDeviceSize(slot) * 16);
            else
                vkCmdDispatch(commands, (std::min(per_dispatch, push.edge_count - first) + kGroupSize - 1) / kGroupSize, 1, 1);
            computeBarrier(commands);
        }
    }

private:
    void destroy();

    VulkanContext& context_;
    std::vector<VkDescriptorType> bindings_;
    uint32_t push_bytes_;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    std::vector<VkPipeline> kernels_;
};

}  // namespace ddt
