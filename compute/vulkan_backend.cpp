#include "vulkan_backend.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <map>
#include <numeric>

#include "buffer.h"
#include "commands.h"
#include "kernels.h"
#include "layout.h"
#include "raster.h"
#include "reconstruct/surface_buffers.h"
#include "reconstruct/surface_passes.h"
#include "simplify/device_simplify.h"
#include "vulkan_error.h"

namespace ddt {

static_assert(sizeof(EdgeVertices) == 16 && sizeof(EdgeNeighbours) == 16, "edge records are uploaded as uvec4");

namespace {

// Largest band of rendered rows held on the device at once.
const VkDeviceSize kBandBytes = VkDeviceSize(64) << 20;
// Loop iterations one render invocation may spend on one triangle: two triangles stay below
// lavapipe's 65535 (see kItemsPerInvocation in glsl/layout.h).
const uint32_t kRasterLoopBudget = 30000;

// How many accept/reject rounds and iterations one submit records. Local-max needs one
// round per iteration; the round-based rules need more rounds, and MaxGain far fewer than
// lowest-id keys (~11 vs ~160 per iteration on a 1024-wide input). Empty dispatches after
// convergence cost little, a host round trip per round would cost more.
struct BatchShape {
    uint32_t rounds_per_iteration;
    uint32_t iterations;
};

BatchShape batchShapeFor(const FlipRule& rule) {
    if (rule.single_round) return {1, 8};
    if (rule.key_by_gain) return {8, 2};
    return {32, 1};
}

std::string mebibytes(uint64_t bytes) { return std::to_string((bytes + (1 << 20) - 1) >> 20) + " MiB"; }

}  // namespace

struct VulkanBackend::State {
    VulkanOptions options;
    FlipRule rule;
    std::unique_ptr<VulkanContext> context;
    Kernels kernels;
    VkQueryPool timestamps = VK_NULL_HANDLE;      // two per optimisation batch: its start and end
    VkQueryPool step_timestamps = VK_NULL_HANDLE; // with profiling: one after every dispatch
    std::vector<const char*> step_labels;         // the kernel each step timestamp closes
    std::map<std::string, KernelTime> kernel_times;

    const Image* image = nullptr;
    uint32_t width = 0, height = 0, edge_count = 0;
    uint32_t vertex_count = 0;                    // the mesh's vertexCount()
    std::vector<Position> explicit_positions;     // the mesh's positions (empty: the grid's places)

    Buffer edge_vertices, edge_neighbours, luma, alpha, gain, status[2], mark, active_list[2], candidate_list,
        round_list[2], control, control_readback, args, partial_sums, pixels, band, row_spans, positions;
    SurfaceBuffers surface;  // the consistent reconstruction's arrays (placeholders until it runs)
    bool quadratic = false;  // render the reconstructed surface, not the input values
    VkDescriptorPool descriptor_pool = VK_NULL_HANDLE;
    VkDescriptorSet descriptor_set = VK_NULL_HANDLE;
    std::vector<uint32_t> spans;  // row_spans downloaded; empty when stale
    std::vector<float> band_texels;  // a rendered band as read back, four floats per pixel

    std::vector<Buffer*> buffers() {
        return {&edge_vertices, &edge_neighbours, &luma,          &alpha,        &gain,          &status[0],
                &status[1],     &mark,            &active_list[0], &active_list[1], &candidate_list, &round_list[0],
                &round_list[1], &control,         &control_readback, &args,      &partial_sums,  &pixels,
                &band,          &row_spans,       &positions};
    }

    void releaseBuffers() {
        for (Buffer* buffer : buffers()) destroyBuffer(*context, *buffer);
        destroySurfaceBuffers(*context, surface);
        quadratic = false;
        if (descriptor_pool) vkDestroyDescriptorPool(context->device, descriptor_pool, nullptr);
        descriptor_pool = VK_NULL_HANDLE;
        descriptor_set = VK_NULL_HANDLE;
        spans.clear();
    }

    KernelBindings bindings() const { return {kernels.layout, descriptor_set}; }
    // The kernels that evaluate costs, specialised for the mesh's places (glsl/common.glsl's kPositioned).
    VkPipeline candidatesKernel() const {
        return explicit_positions.empty() ? kernels.candidates : kernels.positioned_candidates;
    }
    VkPipeline edgeCostKernel() const {
        return explicit_positions.empty() ? kernels.edge_cost : kernels.positioned_edge_cost;
    }

    // The job's scalars; kernel-specific fields are filled by the caller.
    PushConstants push() const {
        PushConstants p{};
        p.width = width;
        p.height = height;
        p.edge_count = edge_count;
        p.has_alpha = image->hasAlpha() ? 1 : 0;
        p.active_set = options.active_set ? 1 : 0;
        p.exproi_iterations = rule.exproi_iterations;
        p.max_iterations = options.max_iterations;
        p.max_rounds = options.max_rounds;
        p.channels = image->channels;
        p.quadratic = quadratic ? 1 : 0;
        return p;
    }

    // What a job keeps on the device: a mesh's vertices (with explicit positions or not) and edges.
    struct JobSize {
        uint64_t vertices = 0, edges = 0;
        bool positioned = false;
    };
    static JobSize gridJob(uint32_t w, uint32_t h) { return {uint64_t(w) * h, gridEdgeCount(w, h), false}; }
    JobSize preparedJob() const { return {vertex_count, edge_count, !explicit_positions.empty()}; }
    struct MemoryNeed {
        uint64_t bytes = 0;
        std::string problem;  // "" or the per-buffer limit the job breaks
    };
    // With `reconstruction`, the consistent reconstruction's arrays too.
    MemoryNeed memoryNeed(const JobSize& job, bool reconstruction) const;
    // Throws DeviceOutOfMemory for a job the device cannot hold; `what` names it ("W×H image").
    void checkMemory(const JobSize& job, bool reconstruction, const std::string& what);
    void checkMemory(uint32_t w, uint32_t h, bool reconstruction) {
        checkMemory(gridJob(w, h), reconstruction, std::to_string(w) + "×" + std::to_string(h) + " image");
    }
    void createBuffers(const Image& image);
    void writeDescriptors();
    void resetOptimisation();
    double meshCost();
    Control readControl();
    void markStep(VkCommandBuffer commands, const char* label);
    void recordStep(VkCommandBuffer commands, uint32_t step, VkPipeline kernel);
    void collectStepTimes();
    void recordIteration(VkCommandBuffer commands, uint32_t rounds, bool candidates, bool flip);
    void recordControlReadback(VkCommandBuffer commands);
    void computeRowSpans();
    // The part of a window one per-triangle dispatch covers: rows × columns keeping every
    // invocation's loops within kRasterLoopBudget.
    struct PartShape {
        uint32_t rows, cols;
    };
    PartShape partShape(const RenderWindow& window) const;
    void recordTrianglePart(VkCommandBuffer commands, VkPipeline kernel, const RenderWindow& window, uint32_t y_begin,
                            uint32_t y_end, uint32_t x_begin, uint32_t x_end);
    void renderPart(const RenderWindow& window, uint32_t y_begin, uint32_t y_end, uint32_t x_begin, uint32_t x_end);
    OptimizeStats finishStats(const Control& control, double cost_init, uint64_t dispatches, double device_ns);
};

VulkanBackend::VulkanBackend(const VulkanOptions& options) : state_(std::make_unique<State>()) {
    State& s = *state_;
    s.options = options;
    std::optional<FlipRule> rule = parseFlipRule(options.rule);
    if (!rule) throw UserError("--variant " + options.rule + ": unknown flip rule");
    s.rule = *rule;
    s.context = createContext({options.device_index, options.validation});
    s.kernels = createKernels(*s.context,
                              {s.rule.key_by_gain ? 1u : 0u, s.rule.single_round ? 1u : 0u, uint32_t(options.cost)});
    if (s.context->timestamps) {
        VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        info.queryType = VK_QUERY_TYPE_TIMESTAMP;
        info.queryCount = 2;
        VK_CHECK(vkCreateQueryPool(s.context->device, &info, nullptr, &s.timestamps));
    }
}

VulkanBackend::~VulkanBackend() {
    State& s = *state_;
    vkDeviceWaitIdle(s.context->device);
    s.releaseBuffers();
    if (s.timestamps) vkDestroyQueryPool(s.context->device, s.timestamps, nullptr);
    if (s.step_timestamps) vkDestroyQueryPool(s.context->device, s.step_timestamps, nullptr);
    destroyKernels(*s.context, s.kernels);
}

const DeviceInfo& VulkanBackend::device() const { return state_->context->info; }
uint32_t VulkanBackend::validationMessages() const { return state_->context->validation_messages.load(); }

// Device memory of a width × height job, and "" or the per-buffer limit it breaks. What
// bites on lavapipe (2 GiB heap, 2 GiB allocations, 2^27 texel-buffer elements; no
// VK_EXT_memory_budget): a 4096² input needs 3.7 GB in all (3 edges and 216 bytes per pixel
// with the default rule, 240 with the round-based ones), beyond the heap, though each array
// fits; an 8192² input has 201 M edges, beyond the texel-buffer elements (and its 3.2 GB
// edge arrays beyond the largest allocation). maxStorageBufferRange (128 MiB) does not
// bite: the big arrays are texel buffers. The consistent reconstruction adds about 708 bytes
// per pixel (compute/reconstruct/surface_buffers.h: 3 × 3 supersamples with their hits, sums
// per half-edge); its supersample arrays reach the texel-buffer elements at 3862² pixels.
// prepare checks the plain need and reconstruct the whole; automatic tiles are sized for the
// surface the upscale asks for. A mesh with explicit positions adds 8 bytes per vertex.
VulkanBackend::State::MemoryNeed VulkanBackend::State::memoryNeed(const JobSize& job, bool reconstruction) const {
    VkPhysicalDeviceMaintenance3Properties maintenance{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &maintenance;
    vkGetPhysicalDeviceProperties2(context->physical, &properties);

    const uint64_t edges = job.edges, vertices = job.vertices;
    const uint64_t per_edge = 16 + 16 + 8 + 2 * 4 + 4 + 4 + (options.active_set ? 2 * 4 : 0) +
                              (rule.single_round ? 0 : 2 * 4);
    // The reconstruction's largest arrays are its 3 × 3 supersamples per pixel.
    const uint64_t elements = reconstruction ? std::max(edges, surfaceBufferLargestElements(vertices, edges)) : edges;
    const uint64_t largest = elements * 16;
    MemoryNeed need;
    // Per vertex: luma, alpha, and the pixel as one rgba32f texel whatever the channels; its
    // position as an rg32i texel where explicit.
    need.bytes = edges * per_edge + vertices * (4 + 4 + 16 + (job.positioned ? 8 : 0)) + kBandBytes +
                 (reconstruction ? surfaceBufferBytes(vertices, edges) : 0);
    if (edges >= kCopyEntry) need.problem = "more edges than the kernels can index";
    else if (elements > context->properties.limits.maxTexelBufferElements)
        need.problem = std::to_string(elements) + (elements == edges ? " edges" : " supersamples") +
                       ", more than the device's " +
                       std::to_string(context->properties.limits.maxTexelBufferElements) + " texel-buffer elements";
    else if (largest > maintenance.maxMemoryAllocationSize)
        need.problem = "its largest arrays need " + mebibytes(largest) + " each, more than the largest allocation of " +
                       mebibytes(maintenance.maxMemoryAllocationSize);
    return need;
}

// Refuses, before allocating anything, a job the device cannot hold: as an out-of-memory
// error, so that a tiled upscale retries with smaller tiles.
void VulkanBackend::State::checkMemory(const JobSize& job, bool reconstruction, const std::string& what) {
    const MemoryNeed need = memoryNeed(job, reconstruction);
    std::string problem = need.problem;
    const uint64_t available = ddt::memoryAvailable(*context);
    if (problem.empty() && need.bytes > available)
        problem = "it needs " + mebibytes(need.bytes) + " of device memory, more than the " + mebibytes(available) +
                  " available";
    if (!problem.empty())
        throw DeviceOutOfMemory(what + " too large for " +
                                context->info.name + ": " + problem + "; try --tile or --backend cpu");
}

uint64_t VulkanBackend::memoryNeeded(uint32_t width, uint32_t height, uint32_t, bool reconstruction) const {
    const State::MemoryNeed need = state_->memoryNeed(State::gridJob(width, height), reconstruction);
    return need.problem.empty() ? need.bytes : UINT64_MAX;
}

uint64_t VulkanBackend::memoryAvailable() const { return ddt::memoryAvailable(*state_->context); }

const Image& VulkanBackend::preparedImage() const { return *state_->image; }

void VulkanBackend::State::createBuffers(const Image& img) {
    VulkanContext& c = *context;
    const uint64_t edges = edge_count, vertices = vertex_count;
    const Placement device = Placement::Device;
    edge_vertices = createBuffer(c, edges * 16, device, VK_FORMAT_R32G32B32A32_UINT);
    edge_neighbours = createBuffer(c, edges * 16, device, VK_FORMAT_R32G32B32A32_UINT);
    luma = createBuffer(c, vertices * 4, device, VK_FORMAT_R32_SFLOAT);
    alpha = createBuffer(c, img.hasAlpha() ? vertices * 4 : 4, device, VK_FORMAT_R32_SFLOAT);
    gain = createBuffer(c, edges * 8, device, VK_FORMAT_R32G32_UINT);
    for (Buffer& b : status) b = createBuffer(c, edges * 4, device, VK_FORMAT_R32_UINT);
    mark = createBuffer(c, edges * 4, device, VK_FORMAT_R32_UINT);
    for (Buffer& b : active_list) b = createBuffer(c, options.active_set ? edges * 4 : 4, device, VK_FORMAT_R32_UINT);
    candidate_list = createBuffer(c, edges * 4, device, VK_FORMAT_R32_UINT);
    for (Buffer& b : round_list) b = createBuffer(c, rule.single_round ? 4 : edges * 4, device, VK_FORMAT_R32_UINT);
    control = createBuffer(c, sizeof(Control));
    control_readback = createBuffer(c, sizeof(Control), Placement::Readback);
    args = createBuffer(c, kArgsCount * 16);
    partial_sums = createBuffer(c, uint64_t(groupsFor(edge_count)) * 8, device, VK_FORMAT_R32G32_UINT);
    pixels = createBuffer(c, vertices * 16, device, VK_FORMAT_R32G32B32A32_SFLOAT);
    row_spans = createBuffer(c, uint64_t(height) * 8 + 4, device, VK_FORMAT_R32_UINT);
    // One texel, never read, for the grid's places.
    positions = createBuffer(c, explicit_positions.empty() ? 8 : vertices * 8, device, VK_FORMAT_R32G32_SINT);
    // A placeholder until the first render sizes it.
    band = createBuffer(c, 16, Placement::Readback, VK_FORMAT_R32G32B32A32_SFLOAT);
    surface = createSurfacePlaceholders(c);

    VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, kBindingCount},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kBindingCount}};
    VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool.maxSets = 1;
    pool.poolSizeCount = 2;
    pool.pPoolSizes = sizes;
    VK_CHECK(vkCreateDescriptorPool(c.device, &pool, nullptr, &descriptor_pool));
    VkDescriptorSetAllocateInfo allocate{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocate.descriptorPool = descriptor_pool;
    allocate.descriptorSetCount = 1;
    allocate.pSetLayouts = &kernels.set_layout;
    VK_CHECK(vkAllocateDescriptorSets(c.device, &allocate, &descriptor_set));
    writeDescriptors();
}

// Points every binding of glsl/layout.h at its buffer (again after the band is resized).
void VulkanBackend::State::writeDescriptors() {
    const Buffer* by_binding[kBindingCount] = {};
    by_binding[kBindingEdgeVertices] = &edge_vertices;
    by_binding[kBindingEdgeNeighbours] = &edge_neighbours;
    by_binding[kBindingLuma] = &luma;
    by_binding[kBindingAlpha] = &alpha;
    by_binding[kBindingGain] = &gain;
    by_binding[kBindingStatus0] = &status[0];
    by_binding[kBindingStatus1] = &status[1];
    by_binding[kBindingMark] = &mark;
    by_binding[kBindingActiveList0] = &active_list[0];
    by_binding[kBindingActiveList1] = &active_list[1];
    by_binding[kBindingCandidateList] = &candidate_list;
    by_binding[kBindingRoundList0] = &round_list[0];
    by_binding[kBindingRoundList1] = &round_list[1];
    by_binding[kBindingPixels] = &pixels;
    by_binding[kBindingBand] = &band;
    by_binding[kBindingRowSpans] = &row_spans;
    by_binding[kBindingPartialSums] = &partial_sums;
    by_binding[kBindingControl] = &control;
    by_binding[kBindingArgs] = &args;
    by_binding[kBindingPositions] = &positions;
    for (uint32_t i = 0; i < kBindingCount; ++i)
        if (const Buffer* b = surface.atBinding(i)) by_binding[i] = b;

    VkWriteDescriptorSet writes[kBindingCount];
    VkDescriptorBufferInfo buffer_infos[kBindingCount];
    for (uint32_t i = 0; i < kBindingCount; ++i) {
        writes[i] = descriptorWrite(descriptor_set, i, bindingType(i));
        if (writes[i].descriptorType == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) {
            buffer_infos[i] = {by_binding[i]->buffer, 0, VK_WHOLE_SIZE};
            writes[i].pBufferInfo = &buffer_infos[i];
        } else {
            writes[i].pTexelBufferView = &by_binding[i]->view;
        }
    }
    vkUpdateDescriptorSets(context->device, kBindingCount, writes, 0, nullptr);
}

void VulkanBackend::prepare(const Image& image) {
    // Checked before the mesh is built: a grid too large for the device is refused at once.
    state_->checkMemory(image.width, image.height, false);
    prepareFrom(image, buildGridMesh(image.width, image.height));
}

// The image holds the vertices' values: pixel v is vertex v's (the grid's image, or for a mesh
// with explicit positions any image of at least vertexCount() pixels).
void VulkanBackend::prepareFrom(const Image& image, Mesh mesh) {
    State& s = *state_;
    assert(mesh.vertexCount() <= uint64_t(image.width) * image.height);
    assert(mesh.positions.empty() || (mesh.width <= kMaxPositionedSide && mesh.height <= kMaxPositionedSide));
    s.releaseBuffers();
    s.image = &image;
    s.width = mesh.width;
    s.height = mesh.height;
    s.edge_count = mesh.edgeCount();
    s.vertex_count = mesh.vertexCount();
    s.explicit_positions = std::move(mesh.positions);
    const std::string what = s.explicit_positions.empty()
                                 ? std::to_string(mesh.width) + "×" + std::to_string(mesh.height) + " image"
                                 : "mesh of " + std::to_string(s.vertex_count) + " points";
    s.checkMemory(s.preparedJob(), false, what);
    VulkanContext& c = *s.context;
    if (!s.explicit_positions.empty()) createPositionedKernels(c, s.kernels);
    const CostField field = costFieldOf(image);
    s.createBuffers(image);
    uploadToBuffer(c, s.edge_vertices, mesh.vertices.data(), s.edge_vertices.size);
    uploadToBuffer(c, s.edge_neighbours, mesh.neighbours.data(), s.edge_neighbours.size);
    uploadToBuffer(c, s.luma, field.luma.data(), s.luma.size);
    if (image.hasAlpha()) uploadToBuffer(c, s.alpha, field.alpha.data(), s.alpha.size);
    if (!s.explicit_positions.empty()) uploadToBuffer(c, s.positions, s.explicit_positions.data(), s.positions.size);
    // One rgba32f texel per vertex: a vertex's channels load at once.
    std::vector<float> texels(size_t(s.vertex_count) * 4, 0.0f);
    for (size_t v = 0; v < s.vertex_count; ++v)
        std::copy_n(image.pixels.data() + v * image.channels, image.channels, texels.data() + v * 4);
    uploadToBuffer(c, s.pixels, texels.data(), s.pixels.size);
}

// Zeroes the statuses, marks and counters: the state at the start of an optimisation.
void VulkanBackend::State::resetOptimisation() {
    CommandBatch commands(*context);
    for (Buffer* b : {&status[0], &status[1], &mark, &control})
        vkCmdFillBuffer(commands.buffer(), b->buffer, 0, VK_WHOLE_SIZE, 0);
    computeBarrier(commands.buffer());
    commands.submitAndWait();
    spans.clear();
    quadratic = false;
}

double VulkanBackend::State::meshCost() {
    CommandBatch commands(*context);
    dispatch(commands.buffer(), edgeCostKernel(), bindings(), push(), groupsFor(edge_count));
    commands.submitAndWait();
    std::vector<double> sums(groupsFor(edge_count));
    downloadFromBuffer(*context, partial_sums, sums.data(), sums.size() * 8);
    return std::accumulate(sums.begin(), sums.end(), 0.0);
}

double VulkanBackend::deviceMeshCost() { return state_->meshCost(); }

std::vector<double> VulkanBackend::deviceEdgeCosts() {
    State& s = *state_;
    CommandBatch commands(*s.context);
    PushConstants p = s.push();
    p.step = 1;
    dispatch(commands.buffer(), s.edgeCostKernel(), s.bindings(), p, groupsFor(s.edge_count));
    commands.submitAndWait();
    std::vector<double> costs(s.edge_count);
    downloadFromBuffer(*s.context, s.gain, costs.data(), costs.size() * 8);
    return costs;
}

std::vector<std::pair<std::string, KernelTime>> VulkanBackend::kernelTimes() const {
    return {state_->kernel_times.begin(), state_->kernel_times.end()};
}

Control VulkanBackend::State::readControl() {
    Control c;
    downloadFromBuffer(*context, control_readback, &c, sizeof(c));
    return c;
}

void VulkanBackend::State::markStep(VkCommandBuffer commands, const char* label) {
    if (!step_timestamps) return;
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, step_timestamps, uint32_t(step_labels.size()));
    step_labels.push_back(label);
}

// A planned step: the plan kernel sizes the step's indirect dispatch, then the step runs.
void VulkanBackend::State::recordStep(VkCommandBuffer commands, uint32_t step, VkPipeline kernel) {
    static const char* const kLabels[] = {"candidates", "select", "flip"};
    PushConstants p = push();
    p.step = step;
    dispatch(commands, kernels.plan, bindings(), p, 1);
    markStep(commands, "plan");
    dispatchIndirect(commands, kernel, bindings(), p, args, step);
    markStep(commands, kLabels[step]);
}

void VulkanBackend::State::collectStepTimes() {
    if (!step_timestamps || step_labels.size() < 2) return;
    std::vector<uint64_t> ticks(step_labels.size());
    VK_CHECK(vkGetQueryPoolResults(context->device, step_timestamps, 0, uint32_t(ticks.size()),
                                   ticks.size() * sizeof(uint64_t), ticks.data(), sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    for (size_t i = 1; i < ticks.size(); ++i) {
        KernelTime& t = kernel_times[step_labels[i]];
        t.dispatches += 1;
        t.ms += double(ticks[i] - ticks[i - 1]) * context->properties.limits.timestampPeriod * 1e-6;
    }
}

void VulkanBackend::State::recordIteration(VkCommandBuffer commands, uint32_t rounds, bool candidates, bool flip) {
    if (candidates) recordStep(commands, kArgsCandidates, candidatesKernel());
    for (uint32_t r = 0; r < rounds; ++r) recordStep(commands, kArgsSelect, kernels.select);
    if (flip) recordStep(commands, kArgsFlip, kernels.flip);
}

void VulkanBackend::State::recordControlReadback(VkCommandBuffer commands) {
    VkBufferCopy region{0, 0, sizeof(Control)};
    vkCmdCopyBuffer(commands, control.buffer, control_readback.buffer, 1, &region);
}

OptimizeStats VulkanBackend::State::finishStats(const Control& c, double cost_init, uint64_t dispatches,
                                                double device_ns) {
    OptimizeStats stats;
    stats.cost_init = cost_init;
    stats.cost_final = meshCost();
    stats.flips = uint64_t(c.total_flips_high) << 32 | c.total_flips_low;
    // Like the serial sweeps, count the last iteration, which found no candidate.
    stats.iterations = c.iteration + (c.capped ? 0 : 1);
    stats.rounds = c.total_rounds;
    stats.max_rounds_in_iteration = c.max_rounds_in_iteration;
    stats.dispatches = dispatches;
    stats.device_ms = device_ns * 1e-6;
    stats.capped = c.capped != 0 || c.phase != kPhaseDone;
    spans.clear();
    return stats;
}

OptimizeStats VulkanBackend::optimize() {
    State& s = *state_;
    VulkanContext& c = *s.context;
    s.resetOptimisation();
    const double cost_init = s.meshCost();

    const BatchShape shape = batchShapeFor(s.rule);
    const uint64_t dispatches_per_batch = uint64_t(shape.iterations) * 2 * (2 + shape.rounds_per_iteration);
    CommandBatch batch(c);
    VkCommandBuffer commands = batch.buffer();
    if (s.timestamps) {
        vkCmdResetQueryPool(commands, s.timestamps, 0, 2);
        vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, s.timestamps, 0);
    }
    if (s.options.profile && s.context->timestamps) {
        if (s.step_timestamps) vkDestroyQueryPool(c.device, s.step_timestamps, nullptr);
        VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        info.queryType = VK_QUERY_TYPE_TIMESTAMP;
        info.queryCount = uint32_t(dispatches_per_batch + 1);
        VK_CHECK(vkCreateQueryPool(c.device, &info, nullptr, &s.step_timestamps));
        vkCmdResetQueryPool(commands, s.step_timestamps, 0, info.queryCount);
        s.step_labels.clear();
        s.markStep(commands, "start");
    }
    for (uint32_t i = 0; i < shape.iterations; ++i) s.recordIteration(commands, shape.rounds_per_iteration, true, true);
    if (s.timestamps) vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, s.timestamps, 1);
    s.recordControlReadback(commands);
    batch.finishRecording();

    // Each submit advances the device's state machine; a loop that cannot end otherwise
    // is bounded by the caps on iterations and rounds.
    const uint64_t max_batches =
        (uint64_t(s.options.max_iterations) + 1) * (s.options.max_rounds / shape.rounds_per_iteration + 2);
    uint64_t batches = 0;
    double device_ns = 0.0;
    Control control{};
    do {
        batch.submitAndWait();
        ++batches;
        if (s.timestamps) {
            uint64_t ticks[2];
            VK_CHECK(vkGetQueryPoolResults(c.device, s.timestamps, 0, 2, sizeof(ticks), ticks, sizeof(uint64_t),
                                           VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
            device_ns += double(ticks[1] - ticks[0]) * c.properties.limits.timestampPeriod;
        }
        s.collectStepTimes();
        control = s.readControl();
    } while (control.phase != kPhaseDone && batches < max_batches);
    return s.finishStats(control, cost_init, batches * dispatches_per_batch, device_ns);
}

OptimizeStats VulkanBackend::optimizeStepwise(const std::function<void(const IterationSnapshot&)>& inspect) {
    State& s = *state_;
    VulkanContext& c = *s.context;
    s.resetOptimisation();
    const double cost_init = s.meshCost();
    uint64_t dispatches = 0;
    auto run = [&](uint32_t rounds, bool candidates, bool flip) {
        CommandBatch batch(c);
        s.recordIteration(batch.buffer(), rounds, candidates, flip);
        s.recordControlReadback(batch.buffer());
        batch.submitAndWait();
        dispatches += 2 * (rounds + candidates + flip);
        return s.readControl();
    };
    auto download = [&](const Buffer& buffer, uint32_t count) {
        std::vector<uint32_t> values(count);
        if (count) downloadFromBuffer(c, buffer, values.data(), count * 4);
        return values;
    };

    Control control = run(1, true, false);
    while (control.phase != kPhaseDone) {
        while (!s.rule.single_round && control.undecided_count[control.round & 1] > 0 &&
               control.round < s.options.max_rounds)
            control = run(1, false, false);

        IterationSnapshot snapshot;
        snapshot.iteration = control.iteration;
        snapshot.rounds = control.round;
        snapshot.mesh = mesh();
        snapshot.candidates = download(s.candidate_list, control.candidate_count);
        std::sort(snapshot.candidates.begin(), snapshot.candidates.end());
        const std::vector<uint32_t> status = download(s.status[control.round & 1], s.edge_count);
        std::vector<double> gains(s.edge_count);
        downloadFromBuffer(c, s.gain, gains.data(), gains.size() * 8);
        for (uint32_t e : snapshot.candidates) {
            snapshot.candidate_gains.push_back(gains[e]);
            if (status[e] == kStatusAccepted) snapshot.accepted.push_back(e);
            if (status[e] == kStatusUndecided) snapshot.undecided.push_back(e);
        }
        inspect(snapshot);

        run(0, false, true);
        control = run(1, true, false);
    }
    return s.finishStats(control, cost_init, dispatches, 0.0);
}

ParallelSimplifyStats VulkanBackend::simplify(Mesh& mesh, Image& values, uint32_t target, double max_error) {
    State& s = *state_;
    // The simplifier's arrays come on top of the optimisation's, which the next prepare frees.
    const uint64_t needed = deviceSimplifierBytes(mesh.edgeCount(), mesh.vertexCount()),
                   held = s.memoryNeed(s.preparedJob(), false).bytes, available = ddt::memoryAvailable(*s.context);
    std::string problem = deviceSimplifierProblem(*s.context, mesh.edgeCount(), mesh.vertexCount());
    if (problem.empty() && needed + held > available)
        problem = "it needs " + mebibytes(needed) + " of device memory beside the optimisation's " + mebibytes(held) +
                  ", more than the " + mebibytes(available) + " available";
    if (!problem.empty())
        throw DeviceOutOfMemory("simplifying the mesh of a " + std::to_string(mesh.width) + "×" +
                                std::to_string(mesh.height) + " image on " + s.context->info.name + ": " + problem +
                                "; try --backend cpu");
    return simplifyOnDevice(*s.context, mesh, values, target, max_error);
}

Mesh VulkanBackend::mesh() {
    State& s = *state_;
    Mesh mesh;
    mesh.width = s.width;
    mesh.height = s.height;
    mesh.positions = s.explicit_positions;
    mesh.vertices.resize(s.edge_count);
    mesh.neighbours.resize(s.edge_count);
    downloadFromBuffer(*s.context, s.edge_vertices, mesh.vertices.data(), s.edge_vertices.size);
    downloadFromBuffer(*s.context, s.edge_neighbours, mesh.neighbours.data(), s.edge_neighbours.size);
    return mesh;
}

void VulkanBackend::State::computeRowSpans() {
    std::vector<uint32_t> initial(2 * size_t(height) + 1, 0);
    for (uint32_t y = 0; y < height; ++y) initial[2 * y] = kNone;  // first row: min over none yet
    uploadToBuffer(*context, row_spans, initial.data(), initial.size() * 4);
    CommandBatch commands(*context);
    dispatch(commands.buffer(), kernels.row_spans, bindings(), push(), groupsFor(edge_count));
    commands.submitAndWait();
    spans.resize(initial.size());
    downloadFromBuffer(*context, row_spans, spans.data(), spans.size() * 4);
}

// Records `kernel`, a per-triangle pass (render.comp's frame), over output rows
// [y_begin, y_end) and columns [x_begin, x_end) of the window: 2D dispatches over the edge
// rows whose triangles may touch them.
void VulkanBackend::State::recordTrianglePart(VkCommandBuffer commands, VkPipeline kernel, const RenderWindow& window,
                                              uint32_t y_begin, uint32_t y_end, uint32_t x_begin, uint32_t x_end) {
    // Crop rows the part samples, and the edge rows whose triangles touch them.
    const OutputSize out = window.out;
    const int64_t unit = vertexCoord(1, out.height);
    const uint32_t v_first = uint32_t(sampleCoord(y_begin, window.input_height, out.height) / unit);
    const uint32_t v_last = uint32_t((sampleCoord(y_end - 1, window.input_height, out.height) + unit - 1) / unit);
    const uint32_t local_first = v_first > window.crop_y ? v_first - window.crop_y : 0;
    const uint32_t local_last = v_last > window.crop_y ? v_last - window.crop_y : 0;
    uint32_t first_row = height, last_row = 0;
    for (uint32_t y = 0; y < height; ++y) {
        if (spans[2 * y] <= local_last && spans[2 * y + 1] >= local_first) {
            first_row = std::min(first_row, y);
            last_row = std::max(last_row, y);
        }
    }
    PushConstants p = push();
    p.first_row = y_begin;
    p.row_count = y_end - y_begin;
    p.first_col = x_begin;
    p.col_count = x_end - x_begin;
    p.out_width = out.width;
    p.out_height = out.height;
    p.input_width = window.input_width;
    p.input_height = window.input_height;
    p.crop_x = window.crop_x;
    p.crop_y = window.crop_y;
    p.band_first_col = window.x_begin;
    p.band_width = window.width();
    const uint32_t groups_per_row = (3 * width - 2 + kGroupSize - 1) / kGroupSize;
    for (uint32_t row = first_row; row <= last_row && first_row <= last_row; row += kMaxGroups) {
        p.first_edge_row = row;
        dispatch2D(commands, kernel, bindings(), p, groups_per_row, std::min(last_row - row + 1, kMaxGroups));
    }
}

// Renders output rows [y_begin, y_end), columns [x_begin, x_end) of the window into the
// band buffer, which holds rows of the window's width from y_begin on.
void VulkanBackend::State::renderPart(const RenderWindow& window, uint32_t y_begin, uint32_t y_end, uint32_t x_begin,
                                      uint32_t x_end) {
    CommandBatch commands(*context);
    recordTrianglePart(commands.buffer(), kernels.render, window, y_begin, y_end, x_begin, x_end);
    commands.submitAndWait();
}

// An invocation rasterises two triangles, each looping over its rows and columns within the
// part; keep that below lavapipe's loop budget (kItemsPerInvocation).
VulkanBackend::State::PartShape VulkanBackend::State::partShape(const RenderWindow& window) const {
    const uint32_t widest =
        uint32_t(std::ceil(double(spans[2 * height] + 1) * window.out.width / window.input_width)) + 2;
    const uint32_t cols = std::min(window.width(), kRasterLoopBudget / 4);
    return {std::max(1u, kRasterLoopBudget / (std::min(widest, cols) + 2) - 1), cols};
}

void VulkanBackend::reconstruct(const DegradationModel& model) {
    static_assert(kSupersamplingFactor == kSupersampling && kSartRelaxation == kRelaxation,
                  "glsl/layout.h follows core/reconstruct.h");
    State& s = *state_;
    VulkanContext& c = *s.context;
    s.checkMemory(s.width, s.height, true);
    if (s.spans.empty()) s.computeRowSpans();
    // The taps are a few numbers from core's own formula: computed here and uploaded.
    const std::vector<float> taps_x = degradationTaps(model.kernel, model.width_x),
                             taps_y = degradationTaps(model.kernel, model.width_y);
    std::vector<float> taps = taps_x;
    taps.insert(taps.end(), taps_y.begin(), taps_y.end());
    destroySurfaceBuffers(c, s.surface);
    s.surface = createSurfaceBuffers(c, s.width, s.height, s.edge_count, uint32_t(taps.size()));
    s.writeDescriptors();
    uploadToBuffer(c, s.surface.taps, taps.data(), taps.size() * 4);

    // The supersampled grid as a window of the renderer: an output of 3w × 3h, crop 0.
    const RenderWindow grid = wholeRows(s.width, s.height, {kSupersampling * s.width, kSupersampling * s.height}, 0,
                                        kSupersampling * s.height);
    const State::PartShape part = s.partShape(grid);
    CommandBatch batch(c);
    SurfacePassJob job;
    job.commands = batch.buffer();
    job.kernels = &s.kernels.reconstruction;
    job.bindings = s.bindings();
    job.push = s.push();
    job.push.taps_x_radius = uint32_t(taps_x.size() / 2);
    job.push.taps_y_radius = uint32_t(taps_y.size() / 2);
    const SampleType type = s.image->sample_type;
    job.push.integer_samples = boundedToUnit(type) ? 1 : 0;
    job.push.quantisation_tolerance = quantisationTolerance(type);
    job.pixels = &s.pixels;
    job.triangle_pass = [&](VkPipeline kernel) {
        for (uint32_t y = 0; y < grid.y_end; y += part.rows)
            for (uint32_t x = 0; x < grid.x_end; x += part.cols)
                s.recordTrianglePart(batch.buffer(), kernel, grid, y, std::min(grid.y_end, y + part.rows), x,
                                     std::min(grid.x_end, x + part.cols));
    };
    recordInitialSurface(job, s.surface);
    if (!model.identity()) recordSartSteps(job, s.surface, kReconstructIterations);
    batch.submitAndWait();
    s.quadratic = true;
}

void VulkanBackend::renderWindow(const RenderWindow& window, float* rows) {
    State& s = *state_;
    if (window.x_begin >= window.x_end || window.y_begin >= window.y_end) return;
    if (s.spans.empty()) s.computeRowSpans();
    const uint32_t window_w = window.width();
    const State::PartShape part = s.partShape(window);
    const VkDeviceSize row_bytes = VkDeviceSize(window_w) * 16;  // an rgba32f texel per pixel
    const VkDeviceSize band_bytes =
        std::min<VkDeviceSize>(kBandBytes, VkDeviceSize(s.context->properties.limits.maxTexelBufferElements) * 16);
    const uint32_t band_rows =
        uint32_t(std::min<VkDeviceSize>(part.rows, std::max<VkDeviceSize>(1, band_bytes / row_bytes)));
    const VkDeviceSize band_needed = std::min<VkDeviceSize>(window.height(), band_rows) * row_bytes;
    if (s.band.size < band_needed) {
        destroyBuffer(*s.context, s.band);
        // The host reads every rendered row: keep the band in host-visible memory.
        s.band = createBuffer(*s.context, band_needed, Placement::Readback, VK_FORMAT_R32G32B32A32_SFLOAT);
        s.writeDescriptors();
    }
    const uint32_t c = s.image->channels;
    for (uint32_t y = window.y_begin; y < window.y_end; y += band_rows) {
        const uint32_t band_end = std::min(window.y_end, y + band_rows);
        for (uint32_t x = window.x_begin; x < window.x_end; x += part.cols)
            s.renderPart(window, y, band_end, x, std::min(window.x_end, x + part.cols));
        // The band holds four floats per pixel; the caller wants `channels`.
        const size_t pixels = size_t(band_end - y) * window_w;
        float* band_rows_out = rows + size_t(y - window.y_begin) * window_w * c;
        if (c == 4) {
            downloadFromBuffer(*s.context, s.band, band_rows_out, pixels * 16);
        } else {
            s.band_texels.resize(pixels * 4);
            downloadFromBuffer(*s.context, s.band, s.band_texels.data(), pixels * 16);
            for (size_t i = 0; i < pixels; ++i) std::copy_n(s.band_texels.data() + 4 * i, c, band_rows_out + c * i);
        }
    }
}

std::unique_ptr<Backend> makeVulkanBackend(const VulkanOptions& options) {
    return std::make_unique<VulkanBackend>(options);
}

}  // namespace ddt
