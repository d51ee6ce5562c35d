#include "kernels.h"

#include <cstddef>

#include "layout.h"
#include "vulkan_error.h"

// SPIR-V written by glslangValidator at build time (see CMakeLists.txt).
#include "spirv/candidates.h"
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
                        const SelectRule& rule) {
    VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    module_info.codeSize = sizeof(spirv);
    module_info.pCode = spirv;
    VkShaderModule module;
    VK_CHECK(vkCreateShaderModule(context.device, &module_info, nullptr, &module));

    const VkSpecializationMapEntry entries[] = {{0, offsetof(SelectRule, key_by_gain), sizeof(uint32_t)},
                                                {1, offsetof(SelectRule, single_round), sizeof(uint32_t)}};
    VkSpecializationInfo specialization{2, entries, sizeof(rule), &rule};
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = &specialization;
    info.layout = layout;
    VkPipeline pipeline;
    VkResult result = vkCreateComputePipelines(context.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
    vkDestroyShaderModule(context.device, module, nullptr);
    VK_CHECK(result);
    return pipeline;
}

}  // namespace

Kernels createKernels(VulkanContext& context, const SelectRule& rule) {
    Kernels k;
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(PushConstants)};
    VkPipelineLayoutCreateInfo layout{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout.pushConstantRangeCount = 1;
    layout.pPushConstantRanges = &range;
    VK_CHECK(vkCreatePipelineLayout(context.device, &layout, nullptr, &k.layout));
    try {
        k.plan = createKernel(context, k.layout, kSpirvPlan, rule);
        k.candidates = createKernel(context, k.layout, kSpirvCandidates, rule);
        k.select = createKernel(context, k.layout, kSpirvSelect, rule);
        k.flip = createKernel(context, k.layout, kSpirvFlip, rule);
        k.edge_cost = createKernel(context, k.layout, kSpirvEdgeCost, rule);
        k.row_spans = createKernel(context, k.layout, kSpirvRowSpans, rule);
        k.render = createKernel(context, k.layout, kSpirvRender, rule);
    } catch (...) {
        destroyKernels(context, k);
        throw;
    }
    return k;
}

void destroyKernels(VulkanContext& context, Kernels& k) {
    for (VkPipeline pipeline : {k.plan, k.candidates, k.select, k.flip, k.edge_cost, k.row_spans, k.render})
        if (pipeline) vkDestroyPipeline(context.device, pipeline, nullptr);
    if (k.layout) vkDestroyPipelineLayout(context.device, k.layout, nullptr);
    k = Kernels{};
}

}  // namespace ddt
