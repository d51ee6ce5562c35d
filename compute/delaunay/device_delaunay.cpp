#include "device_delaunay.h"

#include <cassert>
#include <chrono>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "buffer.h"
#include "canonical_edges.h"
#include "commands.h"
#include "delaunay.h"
#include "delaunay/delaunay_layout.h"
#include "kernel_layout.h"
#include "sweep_triangulation.h"
#include "transfer.h"

// SPIR-V written by glslangValidator at build time (see CMakeLists.txt).
#include "spirv/delaunay_flip.h"
#include "spirv/delaunay_gate.h"
#include "spirv/delaunay_mark.h"
#include "spirv/delaunay_select.h"

namespace ddt {

namespace {

static_assert(sizeof(EdgeVertices) == 4 * 4 && sizeof(EdgeNeighbours) == 4 * 4 && sizeof(Position) == 2 * 4,
              "records and positions are uploaded as they are");

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The device's buffers, destroyed with it.
struct FlipBuffers {
    VulkanContext& context;
    Buffer buffers[kDelaunayBindingCount];

    FlipBuffers(VulkanContext& context, const Mesh& mesh) : context(context) {
        const VkDeviceSize edges = mesh.edgeCount();
        try {
            buffers[kDelaunayBindingEdgeVertices] = createBuffer(context, 16 * edges, Placement::Device, VK_FORMAT_R32_UINT);
            buffers[kDelaunayBindingEdgeNeighbours] =
                createBuffer(context, 16 * edges, Placement::Device, VK_FORMAT_R32_UINT);
            buffers[kDelaunayBindingPositions] =
                createBuffer(context, 8 * mesh.positions.size(), Placement::Device, VK_FORMAT_R32G32_SINT);
            buffers[kDelaunayBindingEdgeStates] = createBuffer(context, 4 * edges, Placement::Device, VK_FORMAT_R32_UINT);
            buffers[kDelaunayBindingTallies] =
                createBuffer(context, 4 * 2 * kDelaunayRoundsPerBatch, Placement::Readback, VK_FORMAT_R32_UINT);
            buffers[kDelaunayBindingEdgeLists] = createBuffer(context, 4 * 2 * edges, Placement::Device, VK_FORMAT_R32_UINT);
            buffers[kDelaunayBindingListLengths] = createBuffer(context, 4 * 2, Placement::Device, VK_FORMAT_R32_UINT);
            buffers[kDelaunayBindingDispatchArgs] = createBuffer(
                context, 16 * 2 * VkDeviceSize(delaunayDispatches(uint32_t(edges))), Placement::Device, VK_FORMAT_R32_UINT);
        } catch (...) {
            destroy();
            throw;
        }
    }
    ~FlipBuffers() { destroy(); }
    FlipBuffers(const FlipBuffers&) = delete;
    FlipBuffers& operator=(const FlipBuffers&) = delete;

    void destroy() {
        for (Buffer& buffer : buffers)
            if (buffer.buffer != VK_NULL_HANDLE) destroyBuffer(context, buffer);
    }
};

// The first round's work: list 0 holds every edge, and the gate, run as if after a round 1
// that had filled list 0, writes its dispatches' group counts.
void startWithEveryEdge(VulkanContext& context, const KernelLayout& layout, VkPipeline gate, FlipBuffers& device,
                        uint32_t edges) {
    std::vector<uint32_t> every_edge(edges);
    std::iota(every_edge.begin(), every_edge.end(), 0u);
    uploadToBuffer(context, device.buffers[kDelaunayBindingEdgeLists], every_edge.data(), 4 * VkDeviceSize(edges));
    const uint32_t lengths[2] = {edges, 0};
    uploadToBuffer(context, device.buffers[kDelaunayBindingListLengths], lengths, sizeof(lengths));
    CommandBatch start(context);
    const DelaunayPush after_round_1{edges, 0, 1, 0};
    layout.bindKernel(start.buffer(), gate, &after_round_1);
    vkCmdDispatch(start.buffer(), 1, 1, 1);
    computeBarrier(start.buffer());  // for the batches' dispatches, later in submission order
    start.finishRecording();
    start.submitAndWait();
}

// Lawson's flips in parallel rounds on the device until every interior edge of `mesh` (positions
// explicit) is locally Delaunay; the records are replaced by the result, numbered as before.
void flipUntilDelaunay(VulkanContext& context, Mesh& mesh, DeviceDelaunayStats& stats) {
    const uint32_t edges = mesh.edgeCount();
    if (uint64_t(4) * edges > context.properties.limits.maxTexelBufferElements)
        throw std::invalid_argument("device delaunay: " + std::to_string(4 * uint64_t(edges)) +
                                    " record words, more than the device's " +
                                    std::to_string(context.properties.limits.maxTexelBufferElements) +
                                    " texel-buffer elements");
    KernelLayout layout(context, std::vector<VkDescriptorType>(kDelaunayBindingCount, VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER),
                        sizeof(DelaunayPush));
    const VkPipeline mark = layout.createKernel(kSpirvDelaunayMark, sizeof(kSpirvDelaunayMark));
    const VkPipeline select = layout.createKernel(kSpirvDelaunaySelect, sizeof(kSpirvDelaunaySelect));
    const VkPipeline flip = layout.createKernel(kSpirvDelaunayFlip, sizeof(kSpirvDelaunayFlip));
    const VkPipeline gate = layout.createKernel(kSpirvDelaunayGate, sizeof(kSpirvDelaunayGate));

    FlipBuffers device(context, mesh);
    uploadToBuffer(context, device.buffers[kDelaunayBindingEdgeVertices], mesh.vertices.data(), 16 * VkDeviceSize(edges));
    uploadToBuffer(context, device.buffers[kDelaunayBindingEdgeNeighbours], mesh.neighbours.data(), 16 * VkDeviceSize(edges));
    uploadToBuffer(context, device.buffers[kDelaunayBindingPositions], mesh.positions.data(), 8 * mesh.positions.size());
    layout.bind(device.buffers);
    startWithEveryEdge(context, layout, gate, device, edges);

    // One batch of rounds, recorded once and submitted until a round marks nothing. Each round
    // goes through its work list with group counts the last round's gate wrote.
    CommandBatch batch(context);
    const Buffer& args = device.buffers[kDelaunayBindingDispatchArgs];
    const uint32_t dispatches = delaunayDispatches(edges);
    vkCmdFillBuffer(batch.buffer(), device.buffers[kDelaunayBindingTallies].buffer, 0, VK_WHOLE_SIZE, 0);
    computeBarrier(batch.buffer());
    for (uint32_t round = 0; round < kDelaunayRoundsPerBatch; ++round) {
        const DelaunayPush push{edges, 0, round, 0};
        for (VkPipeline kernel : {mark, select, flip})
            layout.dispatchPerEdge(batch.buffer(), kernel, push, &args, (round % 2) * dispatches);
        layout.bindKernel(batch.buffer(), gate, &push);
        vkCmdDispatch(batch.buffer(), 1, 1, 1);
        computeBarrier(batch.buffer());
    }
    batch.finishRecording();

    // Flips never bring back an edge flipped away, so there are fewer than one per pair of points.
    const uint64_t most_flips = uint64_t(mesh.vertexCount()) * mesh.vertexCount() / 2;
    for (;;) {
        batch.submitAndWait();
        uint32_t tallies[2 * kDelaunayRoundsPerBatch];
        downloadFromBuffer(context, device.buffers[kDelaunayBindingTallies], tallies, sizeof(tallies));
        bool done = false;
        for (uint32_t round = 0; round < kDelaunayRoundsPerBatch && !done; ++round) {
            const uint32_t marked = tallies[2 * round], flipped = tallies[2 * round + 1];
            done = marked == 0;
            if (!done && flipped == 0) throw std::logic_error("device delaunay: a round with marks flipped nothing");
            stats.rounds += !done;
            stats.flips += flipped;
        }
        if (done) break;
        if (stats.flips > most_flips) throw std::logic_error("device delaunay: more flips than Lawson's bound");
    }
    downloadFromBuffer(context, device.buffers[kDelaunayBindingEdgeVertices], mesh.vertices.data(), 16 * VkDeviceSize(edges));
    downloadFromBuffer(context, device.buffers[kDelaunayBindingEdgeNeighbours], mesh.neighbours.data(),
                       16 * VkDeviceSize(edges));
}

}  // namespace

Mesh deviceDelaunayOfPoints(VulkanContext& context, uint32_t width, uint32_t height, const std::vector<Position>& points,
                            DeviceDelaunayStats* stats) {
    assert(width <= kMaxDelaunaySide && height <= kMaxDelaunaySide);
    assert(delaunayInputProblem(points).empty());
    DeviceDelaunayStats local;
    DeviceDelaunayStats& measured = stats ? *stats : local;
    measured = {};
    auto start = std::chrono::steady_clock::now();
    Mesh mesh = sweepTriangulation(width, height, points);
    measured.sweep_seconds = secondsSince(start);
    start = std::chrono::steady_clock::now();
    flipUntilDelaunay(context, mesh, measured);
    measured.flip_seconds = secondsSince(start);
    start = std::chrono::steady_clock::now();
    renumberCanonically(mesh);
    measured.number_seconds = secondsSince(start);
    return mesh;
}

Mesh deviceDelaunayOfPixels(VulkanContext& context, uint32_t width, uint32_t height,
                            const std::vector<uint32_t>& pixel_ids, DeviceDelaunayStats* stats) {
    std::vector<Position> points(pixel_ids.size());
    for (size_t i = 0; i < pixel_ids.size(); ++i) points[i] = gridPosition(pixel_ids[i], width);
    Mesh mesh = deviceDelaunayOfPoints(context, width, height, points, stats);
    // Local ids ascend with the pixel ids, so the canonical order carries over (as in delaunay.cpp).
    for (EdgeVertices& v : mesh.vertices) {
        v.a = pixel_ids[v.a];
        v.b = pixel_ids[v.b];
        if (v.l != kNone) v.l = pixel_ids[v.l];
        if (v.r != kNone) v.r = pixel_ids[v.r];
    }
    mesh.positions.clear();
    return mesh;
}

}  // namespace ddt
