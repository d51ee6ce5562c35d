// The 2-D DDT's compute kernels (glsl/image/), compiled to SPIR-V at build time and embedded in the
// binary. All share one pipeline layout: the bindings of glsl/layout.h (set 0) and the
// push constants.
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>

#include "context.h"

namespace ddt {

// Specialization constants of the optimisation's kernels: the accept/reject rule (see
// glsl/image/select.comp), the cost (glsl/image/common.glsl's kCost) and where the vertices are (kPositioned).
struct KernelVariant {
    uint32_t key_by_gain = 0;   // MaxGain: higher gain wins; else lower id
    uint32_t single_round = 0;  // local-max: one round per iteration
    uint32_t cost = 0;          // kCostSederberg, kCostVariance or kCostFaceScf (glsl/image/content_cost.h)
    uint32_t positioned = 0;    // 1: the mesh has explicit positions (a VkBool32)
};

// The consistent reconstruction's kernels (glsl/image/reconstruct/, driven by compute/image/reconstruct/).
struct ReconstructionKernels {
    VkPipeline star_starts = VK_NULL_HANDLE;
    VkPipeline value_bounds = VK_NULL_HANDLE;
    VkPipeline initial_bubbles = VK_NULL_HANDLE;
    VkPipeline locate_samples = VK_NULL_HANDLE;
    VkPipeline evaluate_surface = VK_NULL_HANDLE;
    VkPipeline degrade_y = VK_NULL_HANDLE;
    VkPipeline degrade_x = VK_NULL_HANDLE;
    VkPipeline transpose_x = VK_NULL_HANDLE;
    VkPipeline transpose_y = VK_NULL_HANDLE;
    VkPipeline project_triangles = VK_NULL_HANDLE;
    VkPipeline update_values = VK_NULL_HANDLE;
    VkPipeline update_bubbles = VK_NULL_HANDLE;
};

// The convolution fallback's kernels (glsl/image/fallback/, driven by compute/image/device_fallback.cpp).
struct FallbackKernels {
    VkPipeline energy = VK_NULL_HANDLE;
    VkPipeline smooth_x = VK_NULL_HANDLE;
    VkPipeline weights = VK_NULL_HANDLE;
    VkPipeline blend = VK_NULL_HANDLE;
};

struct Kernels {
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline plan = VK_NULL_HANDLE;
    VkPipeline candidates = VK_NULL_HANDLE;
    VkPipeline select = VK_NULL_HANDLE;
    VkPipeline flip = VK_NULL_HANDLE;
    VkPipeline edge_cost = VK_NULL_HANDLE;
    VkPipeline row_spans = VK_NULL_HANDLE;
    VkPipeline render = VK_NULL_HANDLE;
    ReconstructionKernels reconstruction;
    FallbackKernels fallback;
    // The kernels that evaluate costs, candidates and edge_cost, for meshes with explicit
    // positions (kPositioned); made by createPositionedKernels when a job first needs them.
    VkPipeline positioned_candidates = VK_NULL_HANDLE;
    VkPipeline positioned_edge_cost = VK_NULL_HANDLE;
    KernelVariant variant;  // the kernels' specialization
};

// The kernels of `variant` (positioned 0: the grid's).
Kernels createKernels(VulkanContext& context, const KernelVariant& variant);
// Makes positioned_candidates and positioned_edge_cost (variant with positioned 1), unless they exist.
void createPositionedKernels(VulkanContext& context, Kernels& kernels);

// The descriptor type of each binding of glsl/layout.h.
VkDescriptorType bindingType(uint32_t binding);
void destroyKernels(VulkanContext& context, Kernels& kernels);

}  // namespace ddt
