#include "device_simplify.h"

#include <algorithm>
#include <stdexcept>
#include <type_traits>

#include "buffer.h"
#include "commands.h"
#include "simplify_kernels.h"

namespace ddt {

static_assert(kCollapseValenceBound == kMaxCollapseValence, "glsl/simplify/simplify_layout.h follows core");
static_assert(sizeof(Quadric) == kQuadricDoubles * sizeof(double) && std::is_standard_layout_v<Quadric>,
              "quadrics are uploaded as they are");

namespace {

// The arrays of one run, by binding, destroyed with it.
struct SimplifyBuffers {
    VulkanContext& context;
    Buffer at[kSimplifyBindingCount];

    explicit SimplifyBuffers(VulkanContext& c) : context(c) {}
    ~SimplifyBuffers() {
        for (Buffer& buffer : at) destroyBuffer(context, buffer);
    }
    SimplifyBuffers(const SimplifyBuffers&) = delete;
    SimplifyBuffers& operator=(const SimplifyBuffers&) = delete;

    // A texel buffer of `bytes` (at least one texel) holding `data`, if given.
    void make(uint32_t binding, VkDeviceSize bytes, VkFormat format, const void* data,
              Placement placement = Placement::Device) {
        at[binding] = createBuffer(context, std::max<VkDeviceSize>(bytes, 16), placement, format);
        if (data && bytes) uploadToBuffer(context, at[binding], data, bytes);
    }
};

// Every array of a round for the mesh, its walks' starts and quadrics in `start` and the values,
// with room for `collapses` collapse entries.
void makeRoundBuffers(SimplifyBuffers& buffers, const VulkanContext& context, const Mesh& mesh,
                      const SimplifyStart& start, const Image& values, size_t collapses) {
    const uint32_t edges = mesh.edgeCount(), vertices = mesh.vertexCount();
    if (values.channels > kMaxQuadricDimensions - 2 || values.width != mesh.width || values.height != mesh.height)
        throw std::invalid_argument("device simplification: values do not fit the mesh");
    const uint64_t limit = context.properties.limits.maxTexelBufferElements;
    if (uint64_t(vertices) * kQuadricDoubles > limit || edges > limit)
        throw std::invalid_argument("device simplification: the mesh exceeds the device's texel buffers");
    // Channels padded to four floats a vertex, for one rgba32f texel.
    std::vector<float> texels(size_t(vertices) * 4, 0.0f);
    for (size_t v = 0; v < vertices; ++v)
        std::copy_n(values.pixels.data() + v * values.channels, values.channels, texels.data() + 4 * v);
    // The per-edge results the host reads whole are host-visible and cached.
    const VkDeviceSize edge_texels = VkDeviceSize(edges) * 16, vertex_words = VkDeviceSize(vertices) * 4;
    buffers.make(kSimplifyBindingEdgeVertices, edge_texels, VK_FORMAT_R32G32B32A32_UINT, mesh.vertices.data());
    buffers.make(kSimplifyBindingEdgeNeighbours, edge_texels, VK_FORMAT_R32G32B32A32_UINT, mesh.neighbours.data());
    buffers.make(kSimplifyBindingVertexFirst, vertex_words, VK_FORMAT_R32_UINT, start.edges.first.data());
    buffers.make(kSimplifyBindingValues, VkDeviceSize(vertices) * 16, VK_FORMAT_R32G32B32A32_SFLOAT, texels.data());
    buffers.make(kSimplifyBindingQuadrics, VkDeviceSize(vertices) * sizeof(Quadric), VK_FORMAT_R32G32_UINT,
                 start.quadrics.data());
    buffers.make(kSimplifyBindingCandidates, edge_texels, VK_FORMAT_R32G32B32A32_UINT, nullptr, Placement::Readback);
    buffers.make(kSimplifyBindingLeastCost, vertex_words, VK_FORMAT_R32_UINT, nullptr);
    buffers.make(kSimplifyBindingLeastId, vertex_words, VK_FORMAT_R32_UINT, nullptr);
    buffers.make(kSimplifyBindingWinners, VkDeviceSize(edges) * 4, VK_FORMAT_R32_UINT, nullptr, Placement::Readback);
    buffers.make(kSimplifyBindingCollapses, VkDeviceSize(collapses) * 4, VK_FORMAT_R32_UINT, nullptr);
}

}  // namespace

DeviceRoundSelection deviceSelectCollapses(VulkanContext& context, const Mesh& mesh, const SimplifyStart& start,
                                           const Image& values) {
    const uint32_t edges = mesh.edgeCount();
    SimplifyKernels kernels(context);
    SimplifyBuffers buffers(context);
    makeRoundBuffers(buffers, context, mesh, start, values, 0);
    kernels.bind(buffers.at);

    CommandBatch batch(context);
    const VkCommandBuffer commands = batch.buffer();
    SimplifyPush push{mesh.width, mesh.height, values.channels, edges, 0, 0};
    kernels.dispatchPerEdge(commands, kernels.candidates, push);
    for (uint32_t binding : {kSimplifyBindingLeastCost, kSimplifyBindingLeastId})
        vkCmdFillBuffer(commands, buffers.at[binding].buffer, 0, VK_WHOLE_SIZE, kNone);
    computeBarrier(commands);
    for (uint32_t step : {kSelectLeastCost, kSelectLeastId, kSelectWinners}) {
        push.step = step;
        kernels.dispatchPerEdge(commands, kernels.select, push);
    }
    batch.submitAndWait();

    DeviceRoundSelection selection;
    std::vector<uint32_t> words(size_t(edges) * 4), winners(edges);
    if (edges) {
        downloadFromBuffer(context, buffers.at[kSimplifyBindingCandidates], words.data(), words.size() * 4);
        downloadFromBuffer(context, buffers.at[kSimplifyBindingWinners], winners.data(), winners.size() * 4);
    }
    selection.candidates.resize(edges);
    for (uint32_t e = 0; e < edges; ++e) {
        selection.candidates[e] = {uint64_t(words[4 * e]) << 32 | words[4 * e + 1], words[4 * e + 2] != 0};
        if (winners[e]) selection.winners.push_back(e);
    }
    return selection;
}

void deviceCollapse(VulkanContext& context, Mesh& mesh, SimplifyStart& start, const Image& values,
                    const std::vector<Collapse>& collapses) {
    std::vector<uint32_t> entries;
    for (const Collapse& collapse : collapses) {
        if (collapse.edge >= kCollapseBIntoA) throw std::invalid_argument("deviceCollapse: edge id beyond 2^31");
        entries.push_back(collapse.edge | (collapse.b_into_a ? kCollapseBIntoA : 0));
    }
    SimplifyKernels kernels(context);
    SimplifyBuffers buffers(context);
    makeRoundBuffers(buffers, context, mesh, start, values, entries.size());
    if (!entries.empty()) uploadToBuffer(context, buffers.at[kSimplifyBindingCollapses], entries.data(), entries.size() * 4);
    kernels.bind(buffers.at);
    CommandBatch batch(context);
    kernels.dispatchPerEdge(batch.buffer(), kernels.collapse,
                            {mesh.width, mesh.height, values.channels, uint32_t(entries.size()), 0, 0});
    batch.submitAndWait();
    const uint32_t edges = mesh.edgeCount(), vertices = mesh.vertexCount();
    if (edges) {
        downloadFromBuffer(context, buffers.at[kSimplifyBindingEdgeVertices], mesh.vertices.data(), size_t(edges) * 16);
        downloadFromBuffer(context, buffers.at[kSimplifyBindingEdgeNeighbours], mesh.neighbours.data(), size_t(edges) * 16);
    }
    if (vertices) {
        downloadFromBuffer(context, buffers.at[kSimplifyBindingVertexFirst], start.edges.first.data(), size_t(vertices) * 4);
        downloadFromBuffer(context, buffers.at[kSimplifyBindingQuadrics], start.quadrics.data(),
                           size_t(vertices) * sizeof(Quadric));
    }
}

}  // namespace ddt
