#include "device_simplify.h"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <type_traits>

#include "commands.h"
#include "transfer.h"

namespace ddt {

static_assert(kLockedSide == 16, "glsl/simplify/collapse_rule.glsl's sidesAt sets bit 4");
static_assert(kCollapseValenceBound == kMaxCollapseValence, "glsl/simplify/simplify_layout.h follows core");
static_assert(sizeof(Quadric) == kQuadricDoubles * sizeof(double) && std::is_standard_layout_v<Quadric>,
              "quadrics are uploaded as they are");

// Per edge: its two records, candidate, winner entry (16 bytes each, the winner's twice),
// target (8), list entry, collapse entry and state; per vertex id: its walk start, least-key
// words, marks (changed, taken), its position (8), its values (16) and its quadric.
uint64_t deviceSimplifierBytes(uint64_t edges, uint64_t vertices) {
    return edges * (5 * 16 + 8 + 3 * 4) + vertices * (5 * 4 + 8 + 16 + sizeof(Quadric)) + kTallyWords * 4;
}

std::string deviceSimplifierProblem(const VulkanContext& context, uint64_t edges, uint64_t vertices) {
    const uint64_t elements = std::max(2 * edges, vertices * kQuadricDoubles),
                   limit = context.properties.limits.maxTexelBufferElements;
    if (edges >= kCollapseMoves) return "more edges than the kernels can index";
    if (elements > limit)
        return std::to_string(elements) + (elements == 2 * edges ? " winner texels" : " quadric words") + ", more than the device's " +
               std::to_string(limit) + " texel-buffer elements";
    VkPhysicalDeviceMaintenance3Properties maintenance{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &maintenance;
    vkGetPhysicalDeviceProperties2(context.physical, &properties);
    if (const uint64_t quadrics = vertices * sizeof(Quadric); quadrics > maintenance.maxMemoryAllocationSize)
        return "its quadrics need " + std::to_string(quadrics >> 20) + " MiB, more than the largest allocation of " +
               std::to_string(maintenance.maxMemoryAllocationSize >> 20) + " MiB";
    return "";
}

DeviceSimplifier::DeviceSimplifier(VulkanContext& context, const Mesh& mesh, const SimplifyStart& start,
                                   const Image& values, double max_error)
    : context_(context), kernels_(context) {
    const uint32_t edges = mesh.edgeCount(), vertices = mesh.vertexCount();
    // A value per vertex id: the grid's image, or a point file's vertexCount() × 1 values.
    if (values.channels > kMaxQuadricDimensions - 2 || uint64_t(values.width) * values.height != vertices)
        throw std::invalid_argument("device simplification: values do not fit the mesh");
    if (mesh.positions.size() != vertices)
        throw std::invalid_argument("device simplification: the mesh's positions are not explicit");
    if (const std::string problem = deviceSimplifierProblem(context, edges, vertices); !problem.empty())
        throw std::invalid_argument("device simplification: " + problem);
    const uint64_t error_limit = std::bit_cast<uint64_t>(errorLimitOf(max_error));
    push_ = {mesh.width, mesh.height, values.channels, edges, 0, 0, 0, 0, uint32_t(error_limit), uint32_t(error_limit >> 32),
             mesh.locked_sides};
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
        make(kSimplifyBindingPositions, VkDeviceSize(vertices) * 8, VK_FORMAT_R32G32_SINT, mesh.positions.data());
        make(kSimplifyBindingCandidates, edge_texels, VK_FORMAT_R32G32B32A32_UINT, nullptr);
        make(kSimplifyBindingTargets, VkDeviceSize(edges) * 8, VK_FORMAT_R32G32_SINT, nullptr);
        make(kSimplifyBindingLeastCost, vertex_words, VK_FORMAT_R32_UINT, nullptr);
        make(kSimplifyBindingLeastTie, vertex_words, VK_FORMAT_R32_UINT, nullptr);
        make(kSimplifyBindingTaken, vertex_words, VK_FORMAT_R32_UINT, nullptr);
        make(kSimplifyBindingEdgeState, VkDeviceSize(edges) * 4, VK_FORMAT_R32_UINT, nullptr);
        make(kSimplifyBindingWinners, 2 * edge_texels, VK_FORMAT_R32G32B32A32_UINT, nullptr, Placement::Readback);
        make(kSimplifyBindingTallies, kTallyWords * 4, VK_FORMAT_R32_UINT, nullptr, Placement::Readback);
        make(kSimplifyBindingListed, VkDeviceSize(edges) * 4, VK_FORMAT_R32_UINT, nullptr);
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

uint32_t DeviceSimplifier::gatherEdges(uint32_t step, uint32_t cost_word_limit) {
    CommandBatch batch(context_);
    const VkCommandBuffer commands = batch.buffer();
    vkCmdFillBuffer(commands, buffers_[kSimplifyBindingTallies].buffer, 0, VK_WHOLE_SIZE, 0);
    computeBarrier(commands);
    SimplifyPush push = push_;
    push.step = step;
    push.cost_word_limit = cost_word_limit;
    kernels_.dispatchPerEdge(commands, kernels_.gather, push);
    batch.submitAndWait();
    uint32_t count = 0;
    downloadFromBuffer(context_, buffers_[kSimplifyBindingTallies], &count, 4, kTallyListed * 4);
    return count;
}

void DeviceSimplifier::findCandidates() {
    SimplifyPush listed = push_;
    listed.edge_count = gatherEdges(kGatherChanged, 0);
    listed.listed = 1;
    CommandBatch batch(context_);
    const VkCommandBuffer commands = batch.buffer();
    kernels_.dispatchPerEdge(commands, kernels_.candidates, listed);
    SimplifyPush push = push_;
    push.step = kSelectTallyCosts;
    kernels_.dispatchPerEdge(commands, kernels_.select, push);
    batch.submitAndWait();
    cost_tally_.resize(kCostBins);
    downloadFromBuffer(context_, buffers_[kSimplifyBindingTallies], cost_tally_.data(), kCostBins * 4);
}

namespace {

// A candidate from its four words (collapse_candidates.comp) and its target.
CollapseCandidate candidateOf(const uint32_t* words, Position target) {
    const bool moves = (words[2] & kCandidateMoves) != 0;
    return {uint64_t(words[0]) << 32 | words[1], (words[2] & kCandidateBIntoA) != 0, moves, moves ? target : Position{0, 0}};
}

}  // namespace

std::vector<CollapseCandidate> DeviceSimplifier::candidates() const {
    const uint32_t edges = push_.edge_count;
    std::vector<uint32_t> words(size_t(edges) * 4);
    std::vector<Position> targets(edges);
    if (edges) {
        downloadFromBuffer(context_, buffers_[kSimplifyBindingCandidates], words.data(), words.size() * 4);
        downloadFromBuffer(context_, buffers_[kSimplifyBindingTargets], targets.data(), targets.size() * 8);
    }
    std::vector<CollapseCandidate> candidates(edges);
    for (uint32_t e = 0; e < edges; ++e) candidates[e] = candidateOf(&words[4 * e], targets[e]);
    return candidates;
}

std::vector<DeviceWinner> DeviceSimplifier::selectWinners(uint32_t cost_word_limit) {
    SimplifyPush push = push_;
    push.edge_count = gatherEdges(kGatherLimited, cost_word_limit);
    push.listed = 1;
    CommandBatch batch(context_);
    const VkCommandBuffer commands = batch.buffer();
    for (uint32_t binding : {kSimplifyBindingTaken, kSimplifyBindingEdgeState})
        vkCmdFillBuffer(commands, buffers_[binding].buffer, 0, VK_WHOLE_SIZE, 0);
    for (uint32_t pass = 0; pass < kSelectionPasses; ++pass) {
        for (uint32_t binding : {kSimplifyBindingLeastCost, kSimplifyBindingLeastTie})
            vkCmdFillBuffer(commands, buffers_[binding].buffer, 0, VK_WHOLE_SIZE, kNone);
        computeBarrier(commands);
        for (uint32_t step : {kSelectLeastCost, kSelectLeastTie, kSelectWinners, kSelectOut}) {
            push.step = step;
            kernels_.dispatchPerEdge(commands, kernels_.select, push);
        }
    }
    batch.submitAndWait();
    uint32_t count = 0;
    downloadFromBuffer(context_, buffers_[kSimplifyBindingTallies], &count, 4, kTallyWinners * 4);
    std::vector<uint32_t> words(size_t(count) * 8);
    if (count) downloadFromBuffer(context_, buffers_[kSimplifyBindingWinners], words.data(), words.size() * 4);
    std::vector<DeviceWinner> winners(count);
    for (uint32_t i = 0; i < count; ++i) {
        const uint32_t* winner = &words[8 * i];
        winners[i] = {winner[3], candidateOf(winner, {int32_t(winner[4]), int32_t(winner[5])})};
    }
    return winners;
}

void DeviceSimplifier::collapse(const std::vector<Collapse>& collapses) {
    if (collapses.empty()) return;
    std::vector<uint32_t> entries;
    for (const Collapse& collapse : collapses)
        entries.push_back(collapse.edge | (collapse.b_into_a ? kCollapseBIntoA : 0) | (collapse.moves ? kCollapseMoves : 0));
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
    const size_t edges = push_.edge_count, vertices = start.edges.first.size();
    if (edges) {
        downloadFromBuffer(context_, buffers_[kSimplifyBindingEdgeVertices], mesh.vertices.data(), edges * 16);
        downloadFromBuffer(context_, buffers_[kSimplifyBindingEdgeNeighbours], mesh.neighbours.data(), edges * 16);
    }
    downloadFromBuffer(context_, buffers_[kSimplifyBindingVertexFirst], start.edges.first.data(), vertices * 4);
    downloadFromBuffer(context_, buffers_[kSimplifyBindingPositions], mesh.positions.data(), vertices * 8);
    downloadFromBuffer(context_, buffers_[kSimplifyBindingQuadrics], start.quadrics.data(), vertices * sizeof(Quadric));
}

ParallelSimplifyStats simplifyOnDevice(VulkanContext& context, Mesh& mesh, Image& values, uint32_t target,
                                       double max_error) {
    ParallelSimplifyStats stats;
    stats.vertices_before = stats.vertices_after = usedVertexCount(mesh);
    makePositionsExplicit(mesh);
    SimplifyStart start(mesh, values);
    DeviceSimplifier device(context, mesh, start, values, max_error);
    while (stats.vertices_after > target) {
        device.findCandidates();
        const size_t needed = roundCollapses(stats.vertices_after, target);
        std::vector<DeviceWinner> winners =
            device.selectWinners(costWordLimit(device.costTally(), kKeysPerCollapse * needed));
        if (winners.empty()) break;  // no legal collapse left
        // The least of them (core's leastWinners).
        std::sort(winners.begin(), winners.end(),
                  [](const DeviceWinner& x, const DeviceWinner& y) { return x.candidate.key < y.candidate.key; });
        winners.resize(std::min(winners.size(), needed));
        std::vector<Collapse> collapses;
        for (const DeviceWinner& winner : winners) {
            collapses.push_back({winner.edge, winner.candidate.b_into_a, winner.candidate.moves, winner.candidate.target});
            stats.last_cost = std::max(stats.last_cost, collapseKeyCost(winner.candidate.key));
        }
        device.collapse(collapses);
        stats.collapses += collapses.size();
        stats.vertices_after -= uint32_t(collapses.size());
        ++stats.rounds;
    }
    device.download(mesh, start);
    compactEdges(mesh);
    setVertexColours(mesh, start, values);
    return stats;
}

}  // namespace ddt
