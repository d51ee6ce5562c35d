#include "vulkan_backend.h"

#include <algorithm>
#include <cassert>

#include "compute_pipeline.h"
#include "simplify/device_simplify.h"
#include "vulkan_backend_state.h"
#include "vulkan_error.h"

namespace ddt {

static_assert(sizeof(EdgeVertices) == 16 && sizeof(EdgeNeighbours) == 16, "edge records are uploaded as uvec4");

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
// VK_EXT_memory_budget): a 4096² input needs 4.4 GB in all (3 edges and 260 bytes per pixel
// with the default rule, 284 with the round-based ones), beyond the heap, though each array
// fits; an 8192² input has 201 M edges, beyond the texel-buffer elements (and its 3.2 GB
// edge arrays beyond the largest allocation). maxStorageBufferRange (128 MiB) does not
// bite: the big arrays are texel buffers. The consistent reconstruction adds about 708 bytes
// per pixel (compute/image/reconstruct/surface_buffers.h: 3 × 3 supersamples with their hits, sums
// per half-edge); its supersample arrays reach the texel-buffer elements at 3862² pixels.
// prepare checks the plain need and reconstruct the whole; automatic tiles are sized for the
// surface the upscale asks for. A mesh with explicit positions adds 8 bytes per vertex.
VulkanBackend::State::MemoryNeed VulkanBackend::State::memoryNeed(const JobSize& job, bool reconstruction) const {
    VkPhysicalDeviceMaintenance3Properties maintenance{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &maintenance;
    vkGetPhysicalDeviceProperties2(context->physical, &properties);

    const uint64_t edges = job.edges, vertices = job.vertices;
    // Per edge: the records, the gain, the statuses, the mark, the candidate and accepted
    // lists, and the lists the active set and the round-based rules need.
    const uint64_t per_edge = 16 + 16 + 8 + 2 * 4 + 4 + 2 * 4 + (options.active_set ? 2 * 4 : 0) +
                              (rule.single_round ? 0 : 2 * 4);
    // The reconstruction's largest arrays are its 3 × 3 supersamples per pixel.
    const uint64_t elements = reconstruction ? std::max(edges, surfaceBufferLargestElements(vertices, edges)) : edges;
    const uint64_t largest = elements * 16;
    MemoryNeed need;
    // Per vertex: luma, alpha, and the pixel as one rgba32f texel whatever the channels; its
    // position as an rg32i texel where explicit; the convolution fallback's weight and, while
    // it makes them, its structure tensor's pass along x, each an rgba32f texel (counted whether
    // or not it is asked for, as the CPU backend counts its own).
    need.bytes = edges * per_edge + vertices * (4 + 4 + 16 + (job.positioned ? 8 : 0) + 16 + 16) + kBandBytes +
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
    accepted_list = createBuffer(c, edges * 4, device, VK_FORMAT_R32_UINT);
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
    fallback_weights = createBuffer(c, 16, device, VK_FORMAT_R32G32B32A32_SFLOAT);
    fallback_across = createBuffer(c, 16, device, VK_FORMAT_R32G32B32A32_SFLOAT);
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
    by_binding[kBindingAcceptedList] = &accepted_list;
    by_binding[kBindingRoundList0] = &round_list[0];
    by_binding[kBindingRoundList1] = &round_list[1];
    by_binding[kBindingPixels] = &pixels;
    by_binding[kBindingBand] = &band;
    by_binding[kBindingRowSpans] = &row_spans;
    by_binding[kBindingPartialSums] = &partial_sums;
    by_binding[kBindingControl] = &control;
    by_binding[kBindingArgs] = &args;
    by_binding[kBindingPositions] = &positions;
    by_binding[kBindingFallbackWeights] = &fallback_weights;
    by_binding[kBindingFallbackAcross] = &fallback_across;
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
    s.hull = mesh.hull;
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
    mesh.hull = s.hull;
    mesh.vertices.resize(s.edge_count);
    mesh.neighbours.resize(s.edge_count);
    downloadFromBuffer(*s.context, s.edge_vertices, mesh.vertices.data(), s.edge_vertices.size);
    downloadFromBuffer(*s.context, s.edge_neighbours, mesh.neighbours.data(), s.edge_neighbours.size);
    return mesh;
}

std::unique_ptr<Backend> makeVulkanBackend(const VulkanOptions& options) {
    return std::make_unique<VulkanBackend>(options);
}

}  // namespace ddt
