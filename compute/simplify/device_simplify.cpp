#include "device_simplify.h"

#include <algorithm>
#include <stdexcept>
#include <type_traits>

#include "commands.h"

namespace ddt {

static_assert(kCollapseValenceBound == kMaxCollapseValence, "glsl/simplify/simplify_layout.h follows core");
static_assert(sizeof(Quadric) == kQuadricDoubles * sizeof(double) && std::is_standard_layout_v<Quadric>,
              "quadrics are uploaded as they are");

DeviceSimplifier::DeviceSimplifier(VulkanContext& context, const Mesh& mesh, const SimplifyStart& start,
                                   const Image& values)
    : context_(context), kernels_(context) {
    const uint32_t edges = mesh.edgeCount(), vertices = mesh.vertexCount();
    if (values.channels > kMaxQuadricDimensions - 2 || values.width != mesh.width || values.height != mesh.height)
        throw std::invalid_argument("device simplification: values do not fit the mesh");
    const uint64_t limit = context.properties.limits.maxTexelBufferElements;
    if (uint64_t(vertices) * kQuadricDoubles > limit || edges > limit || edges >= kCollapseBIntoA)
        throw std::invalid_argument("device simplification: the mesh exceeds the device's texel buffers");
    push_ = {mesh.width, mesh.height, values.channels, edges, 0, 0};
    // Channels padded to four floats a vertex, for one rgba32f texel.
    std::vector<float> texels(size_t(vertices) * 4, 0.0f);
    for (size_t v = 0; v < vertices; ++v)
        std::copy_n(values.pixels.data() + v * values.channels, values.channels, texels.data() + 4 * v);
    // A texel buffer of `bytes` (at least one texel) holding `data`, if given; the per-edge
    // results the host reads whole each round are host-visible and cached.
    auto make = [&](uint32_t binding, VkDeviceSize bytes, VkFormat format, const void* data,
                    Placement placement = Placement::Device) {
        buffers_[binding] = createBuffer(context, std::max<VkDeviceSize>(bytes, 16), placement, format);
        if (data && bytes) uploadToBuffer(context, buffers_[binding], data, bytes);
    };
    try {
        const VkDeviceSize edge_texels = VkDeviceSize(edges) * 16, vertex_words = VkDeviceSize(vertices) * 4;
        make(kSimplifyBindingEdgeVertices, edge_texels, VK_FORMAT_R32G32B32A32_UINT, mesh.vertices.data());
        make(kSimplifyBindingEdgeNeighbours, edge_texels, VK_FORMAT_R32G32B32A32_UINT, mesh.neighbours.data());
        make(kSimplifyBindingVertexFirst, vertex_words, VK_FORMAT_R32_UINT, start.edges.first.data());
        make(kSimplifyBindingValues, VkDeviceSize(vertices) * 16, VK_FORMAT_R32G32B32A32_SFLOAT, texels.data());
        make(kSimplifyBindingQuadrics, VkDeviceSize(vertices) * sizeof(Quadric), VK_FORMAT_R32G32_UINT,
             start.quadrics.data());
        make(kSimplifyBindingCandidates, edge_texels, VK_FORMAT_R32G32B32A32_UINT, nullptr, Placement::Readback);
        make(kSimplifyBindingLeastCost, vertex_words, VK_FORMAT_R32_UINT, nullptr);
        make(kSimplifyBindingLeastId, vertex_words, VK_FORMAT_R32_UINT, nullptr);
        make(kSimplifyBindingWinners, VkDeviceSize(edges) * 4, VK_FORMAT_R32_UINT, nullptr, Placement::Readback);
        // Winners' regions are disjoint, so a round has fewer collapses than edges.
        make(kSimplifyBindingCollapses, VkDeviceSize(edges) * 4, VK_FORMAT_R32_UINT, nullptr);
        // Every vertex counts as changed before the first round: every edge gets a candidate.
        const std::vector<uint32_t> all_changed(vertices, 1);
        make(kSimplifyBindingChanged, vertex_words, VK_FORMAT_R32_UINT, all_changed.data());
    } catch (...) {
        for (Buffer& buffer : buffers_) destroyBuffer(context, buffer);
        throw;
    }
    kernels_.bind(buffers_);
}

DeviceSimplifier::~DeviceSimplifier() {
    for (Buffer& buffer : buffers_) destroyBuffer(context_, buffer);
}

DeviceRoundSelection DeviceSimplifier::select() {
    const uint32_t edges = push_.edge_count;
    CommandBatch batch(context_);
    const VkCommandBuffer commands = batch.buffer();
    SimplifyPush push = push_;
    kernels_.dispatchPerEdge(commands, kernels_.candidates, push);
    for (uint32_t binding : {kSimplifyBindingLeastCost, kSimplifyBindingLeastId})
        vkCmdFillBuffer(commands, buffers_[binding].buffer, 0, VK_WHOLE_SIZE, kNone);
    computeBarrier(commands);
    for (uint32_t step : {kSelectLeastCost, kSelectLeastId, kSelectWinners}) {
        push.step = step;
        kernels_.dispatchPerEdge(commands, kernels_.select, push);
    }
    batch.submitAndWait();

    DeviceRoundSelection selection;
    std::vector<uint32_t> words(size_t(edges) * 4), winners(edges);
    if (edges) {
        downloadFromBuffer(context_, buffers_[kSimplifyBindingCandidates], words.data(), words.size() * 4);
        downloadFromBuffer(context_, buffers_[kSimplifyBindingWinners], winners.data(), winners.size() * 4);
    }
    selection.candidates.resize(edges);
    for (uint32_t e = 0; e < edges; ++e) {
        selection.candidates[e] = {uint64_t(words[4 * e]) << 32 | words[4 * e + 1], words[4 * e + 2] != 0};
        if (winners[e]) selection.winners.push_back(e);
    }
    return selection;
}

void DeviceSimplifier::collapse(const std::vector<Collapse>& collapses) {
    if (collapses.empty()) return;
    std::vector<uint32_t> entries;
    for (const Collapse& collapse : collapses) entries.push_back(collapse.edge | (collapse.b_into_a ? kCollapseBIntoA : 0));
    if (entries.size() > push_.edge_count) throw std::invalid_argument("DeviceSimplifier: more collapses than edges");
    uploadToBuffer(context_, buffers_[kSimplifyBindingCollapses], entries.data(), entries.size() * 4);
    CommandBatch batch(context_);
    vkCmdFillBuffer(batch.buffer(), buffers_[kSimplifyBindingChanged].buffer, 0, VK_WHOLE_SIZE, 0);
    computeBarrier(batch.buffer());
    SimplifyPush push = push_;
    push.edge_count = uint32_t(entries.size());
    kernels_.dispatchPerEdge(batch.buffer(), kernels_.collapse, push);
    batch.submitAndWait();
}

void DeviceSimplifier::download(Mesh& mesh, SimplifyStart& start) const {
    const size_t edges = push_.edge_count, vertices = size_t(push_.width) * push_.height;
    if (edges) {
        downloadFromBuffer(context_, buffers_[kSimplifyBindingEdgeVertices], mesh.vertices.data(), edges * 16);
        downloadFromBuffer(context_, buffers_[kSimplifyBindingEdgeNeighbours], mesh.neighbours.data(), edges * 16);
    }
    downloadFromBuffer(context_, buffers_[kSimplifyBindingVertexFirst], start.edges.first.data(), vertices * 4);
    downloadFromBuffer(context_, buffers_[kSimplifyBindingQuadrics], start.quadrics.data(), vertices * sizeof(Quadric));
}

ParallelSimplifyStats simplifyOnDevice(VulkanContext& context, Mesh& mesh, Image& values, uint32_t target) {
    ParallelSimplifyStats stats;
    stats.vertices_before = stats.vertices_after = usedVertexCount(mesh);
    SimplifyStart start(mesh, values);
    DeviceSimplifier device(context, mesh, start, values);
    std::vector<uint64_t> keys(mesh.edgeCount());
    while (stats.vertices_after > target) {
        DeviceRoundSelection round = device.select();
        if (round.winners.empty()) break;  // no legal collapse left
        for (size_t e = 0; e < keys.size(); ++e) keys[e] = round.candidates[e].key;
        leastWinners(round.winners, keys, stats.vertices_after, target);
        std::vector<Collapse> collapses;
        for (uint32_t e : round.winners) {
            collapses.push_back({e, round.candidates[e].b_into_a});
            stats.last_cost = std::max(stats.last_cost, collapseKeyCost(keys[e]));
        }
        device.collapse(collapses);
        stats.collapses += collapses.size();
        stats.vertices_after -= uint32_t(collapses.size());
        ++stats.rounds;
    }
    device.download(mesh, start);
    compactEdges(mesh);
    setBestColours(mesh, start.quadrics, start.points, values);
    return stats;
}

}  // namespace ddt
