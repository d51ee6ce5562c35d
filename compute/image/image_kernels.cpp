#include "image_kernels.h"

#include <cstddef>

#include "compute_pipeline.h"
#include "layout.h"
#include "vulkan_error.h"

// SPIR-V written by glslangValidator at build time (see CMakeLists.txt).
#include "spirv/candidates.h"
#include "spirv/degrade_x.h"
#include "spirv/degrade_y.h"
#include "spirv/evaluate_surface.h"
#include "spirv/fallback_blend.h"
#include "spirv/fallback_energy.h"
#include "spirv/fallback_smooth_x.h"
#include "spirv/fallback_weights.h"
#include "spirv/initial_bubbles.h"
#include "spirv/locate_samples.h"
#include "spirv/project_triangles.h"
#include "spirv/star_starts.h"
#include "spirv/transpose_x.h"
#include "spirv/transpose_y.h"
#include "spirv/update_bubbles.h"
#include "spirv/update_values.h"
#include "spirv/value_bounds.h"
#include "spirv/edge_cost.h"
#include "spirv/flip.h"
#include "spirv/plan.h"
#include "spirv/render.h"
#include "spirv/row_spans.h"
#include "spirv/select.h"

namespace ddt {

namespace {

template <size_t N>
VkPipeline createKernel(VulkanContext& context, VkPipelineLayout layout, const uint32_t (&spirv)[N],
                        const KernelVariant& variant) {
    const VkSpecializationMapEntry entries[] = {{0, offsetof(KernelVariant, key_by_gain), sizeof(uint32_t)},
                                                {1, offsetof(KernelVariant, single_round), sizeof(uint32_t)},
                                                {2, offsetof(KernelVariant, cost), sizeof(uint32_t)},
                                                {3, offsetof(KernelVariant, positioned), sizeof(VkBool32)}};
    const VkSpecializationInfo specialization{4, entries, sizeof(variant), &variant};
    return createComputePipeline(context, layout, spirv, sizeof(spirv), &specialization);
}

}  // namespace

VkDescriptorType bindingType(uint32_t binding) {
    return binding == kBindingControl || binding == kBindingArgs ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                                                                 : VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
}

Kernels createKernels(VulkanContext& context, const KernelVariant& variant) {
    Kernels k;
    k.variant = variant;
    VkDescriptorSetLayoutBinding bindings[kBindingCount];
    for (uint32_t i = 0; i < kBindingCount; ++i)
        bindings[i] = {i, bindingType(i), 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo set_layout{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    set_layout.bindingCount = kBindingCount;
    set_layout.pBindings = bindings;
    VK_CHECK(vkCreateDescriptorSetLayout(context.device, &set_layout, nullptr, &k.set_layout));

    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(PushConstants)};
    VkPipelineLayoutCreateInfo layout{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout.setLayoutCount = 1;
    layout.pSetLayouts = &k.set_layout;
    layout.pushConstantRangeCount = 1;
    layout.pPushConstantRanges = &range;
    VK_CHECK(vkCreatePipelineLayout(context.device, &layout, nullptr, &k.layout));
    try {
        k.plan = createKernel(context, k.layout, kSpirvPlan, variant);
        k.candidates = createKernel(context, k.layout, kSpirvCandidates, variant);
        k.select = createKernel(context, k.layout, kSpirvSelect, variant);
        k.flip = createKernel(context, k.layout, kSpirvFlip, variant);
        k.edge_cost = createKernel(context, k.layout, kSpirvEdgeCost, variant);
        k.row_spans = createKernel(context, k.layout, kSpirvRowSpans, variant);
        k.render = createKernel(context, k.layout, kSpirvRender, variant);
        ReconstructionKernels& r = k.reconstruction;
        r.star_starts = createKernel(context, k.layout, kSpirvStarStarts, variant);
        r.value_bounds = createKernel(context, k.layout, kSpirvValueBounds, variant);
        r.initial_bubbles = createKernel(context, k.layout, kSpirvInitialBubbles, variant);
        r.locate_samples = createKernel(context, k.layout, kSpirvLocateSamples, variant);
        r.evaluate_surface = createKernel(context, k.layout, kSpirvEvaluateSurface, variant);
        r.degrade_y = createKernel(context, k.layout, kSpirvDegradeY, variant);
        r.degrade_x = createKernel(context, k.layout, kSpirvDegradeX, variant);
        r.transpose_x = createKernel(context, k.layout, kSpirvTransposeX, variant);
        r.transpose_y = createKernel(context, k.layout, kSpirvTransposeY, variant);
        r.project_triangles = createKernel(context, k.layout, kSpirvProjectTriangles, variant);
        r.update_values = createKernel(context, k.layout, kSpirvUpdateValues, variant);
        r.update_bubbles = createKernel(context, k.layout, kSpirvUpdateBubbles, variant);
        FallbackKernels& f = k.fallback;
        f.energy = createKernel(context, k.layout, kSpirvFallbackEnergy, variant);
        f.smooth_x = createKernel(context, k.layout, kSpirvFallbackSmoothX, variant);
        f.weights = createKernel(context, k.layout, kSpirvFallbackWeights, variant);
        f.blend = createKernel(context, k.layout, kSpirvFallbackBlend, variant);
    } catch (...) {
        destroyKernels(context, k);
        throw;
    }
    return k;
}

void createPositionedKernels(VulkanContext& context, Kernels& k) {
    if (k.positioned_candidates) return;
    KernelVariant variant = k.variant;
    variant.positioned = 1;
    k.positioned_candidates = createKernel(context, k.layout, kSpirvCandidates, variant);
    k.positioned_edge_cost = createKernel(context, k.layout, kSpirvEdgeCost, variant);
}

void destroyKernels(VulkanContext& context, Kernels& k) {
    const ReconstructionKernels& r = k.reconstruction;
    const FallbackKernels& f = k.fallback;
    for (VkPipeline pipeline : {k.plan, k.candidates, k.select, k.flip, k.edge_cost, k.row_spans, k.render,
                                k.positioned_candidates, k.positioned_edge_cost,
                                r.star_starts, r.value_bounds, r.initial_bubbles, r.locate_samples, r.evaluate_surface,
                                r.degrade_y, r.degrade_x, r.transpose_x, r.transpose_y, r.project_triangles,
                                r.update_values, r.update_bubbles, f.energy, f.smooth_x, f.weights, f.blend})
        if (pipeline) vkDestroyPipeline(context.device, pipeline, nullptr);
    if (k.layout) vkDestroyPipelineLayout(context.device, k.layout, nullptr);
    if (k.set_layout) vkDestroyDescriptorSetLayout(context.device, k.set_layout, nullptr);
    k = Kernels{};
}

}  // namespace ddt
