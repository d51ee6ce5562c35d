#include "collapse_candidates.h"

#include <algorithm>
#include <stdexcept>
#include <type_traits>

#include "buffer.h"
#include "commands.h"
#include "kernels.h"
#include "simplify/simplify_layout.h"
#include "vulkan_error.h"

// SPIR-V written by glslangValidator at build time (see CMakeLists.txt).
#include "spirv/collapse_candidates.h"

namespace ddt {

static_assert(kCollapseValenceBound == kMaxCollapseValence, "glsl/simplify/simplify_layout.h follows core");
static_assert(sizeof(Quadric) == kQuadricDoubles * sizeof(double) && std::is_standard_layout_v<Quadric>,
              "quadrics are uploaded as they are");

namespace {

// The kernels' descriptor set layout, pipeline layout and pipeline, destroyed with it.
struct CandidateKernel {
    VulkanContext& context;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;

    explicit CandidateKernel(VulkanContext& c) : context(c) {
        VkDescriptorSetLayoutBinding bindings[kSimplifyBindingCount];
        for (uint32_t i = 0; i < kSimplifyBindingCount; ++i)
            bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
        VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        set_info.bindingCount = kSimplifyBindingCount;
        set_info.pBindings = bindings;
        VK_CHECK(vkCreateDescriptorSetLayout(c.device, &set_info, nullptr, &set_layout));
        VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(SimplifyPush)};
        VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        layout_info.setLayoutCount = 1;
        layout_info.pSetLayouts = &set_layout;
        layout_info.pushConstantRangeCount = 1;
        layout_info.pPushConstantRanges = &range;
        VK_CHECK(vkCreatePipelineLayout(c.device, &layout_info, nullptr, &layout));
        pipeline = createComputePipeline(c, layout, kSpirvCollapseCandidates, sizeof(kSpirvCollapseCandidates));
        VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, kSimplifyBindingCount};
        VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pool_info.maxSets = 1;
        pool_info.poolSizeCount = 1;
        pool_info.pPoolSizes = &size;
        VK_CHECK(vkCreateDescriptorPool(c.device, &pool_info, nullptr, &pool));
        VkDescriptorSetAllocateInfo allocate{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        allocate.descriptorPool = pool;
        allocate.descriptorSetCount = 1;
        allocate.pSetLayouts = &set_layout;
        VK_CHECK(vkAllocateDescriptorSets(c.device, &allocate, &set));
    }
    ~CandidateKernel() {
        if (pool) vkDestroyDescriptorPool(context.device, pool, nullptr);
        if (pipeline) vkDestroyPipeline(context.device, pipeline, nullptr);
        if (layout) vkDestroyPipelineLayout(context.device, layout, nullptr);
        if (set_layout) vkDestroyDescriptorSetLayout(context.device, set_layout, nullptr);
    }
    CandidateKernel(const CandidateKernel&) = delete;
    CandidateKernel& operator=(const CandidateKernel&) = delete;
};

// The buffers of one run, destroyed with it.
struct CandidateBuffers {
    VulkanContext& context;
    Buffer at[kSimplifyBindingCount];

    explicit CandidateBuffers(VulkanContext& c) : context(c) {}
    ~CandidateBuffers() {
        for (Buffer& buffer : at) destroyBuffer(context, buffer);
    }
    CandidateBuffers(const CandidateBuffers&) = delete;
    CandidateBuffers& operator=(const CandidateBuffers&) = delete;

    // A texel buffer of `bytes` (at least one texel) holding `data`, if given.
    void make(uint32_t binding, VkDeviceSize bytes, VkFormat format, const void* data, Placement placement) {
        at[binding] = createBuffer(context, std::max<VkDeviceSize>(bytes, 16), placement, format);
        if (data && bytes) uploadToBuffer(context, at[binding], data, bytes);
    }
};

}  // namespace

std::vector<CollapseCandidate> deviceCollapseCandidates(VulkanContext& context, const Mesh& mesh,
                                                        const SimplifyStart& start, const Image& values) {
    const uint32_t edges = mesh.edgeCount(), vertices = mesh.vertexCount();
    if (values.channels > kMaxQuadricDimensions - 2 || values.width != mesh.width || values.height != mesh.height)
        throw std::invalid_argument("deviceCollapseCandidates: values do not fit the mesh");
    const uint64_t limit = context.properties.limits.maxTexelBufferElements;
    if (uint64_t(vertices) * kQuadricDoubles > limit || edges > limit)
        throw std::invalid_argument("deviceCollapseCandidates: the mesh exceeds the device's texel buffers");

    // Channels padded to four floats a vertex, for one rgba32f texel.
    std::vector<float> texels(size_t(vertices) * 4, 0.0f);
    for (size_t v = 0; v < vertices; ++v)
        std::copy_n(values.pixels.data() + v * values.channels, values.channels, texels.data() + 4 * v);
    CandidateKernel kernel(context);
    CandidateBuffers buffers(context);
    buffers.make(kSimplifyBindingEdgeVertices, VkDeviceSize(edges) * 16, VK_FORMAT_R32G32B32A32_UINT,
                 mesh.vertices.data(), Placement::Device);
    buffers.make(kSimplifyBindingEdgeNeighbours, VkDeviceSize(edges) * 16, VK_FORMAT_R32G32B32A32_UINT,
                 mesh.neighbours.data(), Placement::Device);
    buffers.make(kSimplifyBindingVertexFirst, VkDeviceSize(vertices) * 4, VK_FORMAT_R32_UINT,
                 start.edges.first.data(), Placement::Device);
    buffers.make(kSimplifyBindingValues, VkDeviceSize(vertices) * 16, VK_FORMAT_R32G32B32A32_SFLOAT, texels.data(),
                 Placement::Device);
    buffers.make(kSimplifyBindingQuadrics, VkDeviceSize(vertices) * sizeof(Quadric), VK_FORMAT_R32G32_UINT,
                 start.quadrics.data(), Placement::Device);
    buffers.make(kSimplifyBindingCandidates, VkDeviceSize(edges) * 16, VK_FORMAT_R32G32B32A32_UINT, nullptr,
                 Placement::Readback);

    VkWriteDescriptorSet writes[kSimplifyBindingCount];
    for (uint32_t i = 0; i < kSimplifyBindingCount; ++i) {
        writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[i].dstSet = kernel.set;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
        writes[i].pTexelBufferView = &buffers.at[i].view;
    }
    vkUpdateDescriptorSets(context.device, kSimplifyBindingCount, writes, 0, nullptr);

    // One invocation an edge, at most kMaxGroups groups a dispatch.
    CommandBatch batch(context);
    const VkCommandBuffer commands = batch.buffer();
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.pipeline);
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.layout, 0, 1, &kernel.set, 0, nullptr);
    const uint32_t per_dispatch = kMaxGroups * kGroupSize;
    for (uint32_t first = 0; first < edges; first += std::min(per_dispatch, edges - first)) {
        const SimplifyPush push{mesh.width, mesh.height, values.channels, edges, first};
        vkCmdPushConstants(commands, kernel.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
        vkCmdDispatch(commands, (std::min(per_dispatch, edges - first) + kGroupSize - 1) / kGroupSize, 1, 1);
    }
    batch.submitAndWait();

    std::vector<uint32_t> words(size_t(edges) * 4);
    if (edges) downloadFromBuffer(context, buffers.at[kSimplifyBindingCandidates], words.data(), words.size() * 4);
    std::vector<CollapseCandidate> candidates(edges);
    for (size_t e = 0; e < edges; ++e)
        candidates[e] = {uint64_t(words[4 * e]) << 32 | words[4 * e + 1], words[4 * e + 2] != 0};
    return candidates;
}

}  // namespace ddt
