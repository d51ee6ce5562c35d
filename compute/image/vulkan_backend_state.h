// The Vulkan backend's state, shared by the files that implement its stages:
// vulkan_backend.cpp (device, buffers, the mesh up and down), device_optimize.cpp (the flips),
// device_reconstruct.cpp (the consistent surface), device_render.cpp (the output rows) and
// device_fallback.cpp (the convolution fallback).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "buffer.h"
#include "commands.h"
#include "image_kernels.h"
#include "layout.h"
#include "memory_size.h"
#include "reconstruct/surface_buffers.h"
#include "transfer.h"
#include "vulkan_backend.h"

namespace ddt {

// Largest band of rendered rows held on the device at once.
inline constexpr VkDeviceSize kBandBytes = VkDeviceSize(64) << 20;
// Loop iterations one render invocation may spend on one triangle: two triangles stay below
// lavapipe's 65535 (see kItemsPerInvocation in glsl/layout.h).
inline constexpr uint32_t kRasterLoopBudget = 30000;

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
    MeshHull hull = MeshHull::rectangle;          // the mesh's, handed back by mesh()
    bool delaunay_on_device = false;              // where the last delaunayPixels or delaunayPoints ran

    Buffer edge_vertices, edge_neighbours, luma, alpha, gain, status[2], mark, active_list[2], candidate_list,
        accepted_list, round_list[2], control, control_readback, args, partial_sums, pixels, band, row_spans, positions,
        fallback_weights, fallback_across;  // the fallback's: placeholders until addFallback
    SurfaceBuffers surface;  // the consistent reconstruction's arrays (placeholders until it runs)
    bool quadratic = false;  // render the reconstructed surface, not the input values
    bool fallback = false;   // blend each rendered band towards Lanczos3 (addFallback)
    VkDescriptorPool descriptor_pool = VK_NULL_HANDLE;
    VkDescriptorSet descriptor_set = VK_NULL_HANDLE;
    std::vector<uint32_t> spans;  // row_spans downloaded; empty when stale
    std::vector<float> band_texels;  // a rendered band as read back, four floats per pixel

    std::vector<Buffer*> buffers() {
        return {&edge_vertices,  &edge_neighbours, &luma,          &alpha,          &gain,
                &status[0],      &status[1],       &mark,          &active_list[0], &active_list[1],
                &candidate_list, &accepted_list,   &round_list[0], &round_list[1],  &control,
                &control_readback, &args,          &partial_sums,  &pixels,         &band,
                &row_spans,      &positions,       &fallback_weights, &fallback_across};
    }

    void releaseBuffers() {
        for (Buffer* buffer : buffers()) destroyBuffer(*context, *buffer);
        destroySurfaceBuffers(*context, surface);
        quadratic = false;
        fallback = false;
        if (descriptor_pool) vkDestroyDescriptorPool(context->device, descriptor_pool, nullptr);
        descriptor_pool = VK_NULL_HANDLE;
        descriptor_set = VK_NULL_HANDLE;
        spans.clear();
    }

    KernelBindings bindings() const { return {kernels.layout, descriptor_set}; }
    // The kernels that evaluate costs, specialised for the mesh's places (glsl/image/common.glsl's kPositioned).
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
    // Adds the last batch's step times to kernel_times; its first iteration is `first_iteration`.
    void collectStepTimes(uint32_t first_iteration);
    void recordIteration(VkCommandBuffer commands, uint32_t rounds, bool candidates, bool flip);
    void recordControlReadback(VkCommandBuffer commands);
    void computeRowSpans();
    // The part of a window one per-triangle dispatch covers: rows × columns keeping every
    // invocation's loops within kRasterLoopBudget.
    struct PartShape {
        uint32_t rows, cols;
    };
    PartShape partShape(const RenderWindow& window) const;
    // The job's scalars with the window's: the whole output and input, the crop, the band's columns.
    PushConstants windowPush(const RenderWindow& window) const;
    void recordTrianglePart(VkCommandBuffer commands, VkPipeline kernel, const RenderWindow& window, uint32_t y_begin,
                            uint32_t y_end, uint32_t x_begin, uint32_t x_end);
    void renderPart(const RenderWindow& window, uint32_t y_begin, uint32_t y_end, uint32_t x_begin, uint32_t x_end);
    // Blends the window's rows [y_begin, y_end), rendered into the band, towards Lanczos3.
    void blendBand(const RenderWindow& window, uint32_t y_begin, uint32_t y_end);
    OptimizeStats finishStats(const Control& control, double cost_init, uint64_t dispatches, double device_ns);
};

}  // namespace ddt
