#include "surface_passes.h"

#include <cstring>

#include "layout.h"
#include "mesh.h"

namespace ddt {

namespace {

uint32_t floatBits(float value) {
    uint32_t bits;
    std::memcpy(&bits, &value, 4);
    return bits;
}

void fill(VkCommandBuffer commands, const Buffer& buffer, uint32_t word) {
    vkCmdFillBuffer(commands, buffer.buffer, 0, VK_WHOLE_SIZE, word);
}

// One pass over `count` items (pixels, edges or supersamples).
void over(const SurfacePassJob& job, VkPipeline kernel, uint32_t count, uint32_t step = 0) {
    PushConstants p = job.push;
    p.step = step;
    dispatch(job.commands, kernel, job.bindings, p, groupsFor(count));
}

// ρ (the supersamples) projected onto every vertex value and bubble: stored as the weights
// (step 0) or applied as a SART step (step 1).
void recordProjection(const SurfacePassJob& job, SurfaceBuffers& buffers, uint32_t step) {
    const ReconstructionKernels& k = *job.kernels;
    fill(job.commands, buffers.half_edge_value_sums, 0);
    fill(job.commands, buffers.half_edge_bubble_sums, 0);
    computeBarrier(job.commands);
    job.triangle_pass(k.project_triangles);
    over(job, k.update_values, job.push.width * job.push.height, step);
    over(job, k.update_bubbles, job.push.edge_count, step);
}

// Dᵀ of the residual, onto the supersamples.
void recordTranspose(const SurfacePassJob& job) {
    const uint32_t sub_w = kSupersamplingFactor * job.push.width, sub_h = kSupersamplingFactor * job.push.height;
    over(job, job.kernels->transpose_x, sub_w * job.push.height);
    over(job, job.kernels->transpose_y, sub_w * sub_h);
}

}  // namespace

void recordInitialSurface(const SurfacePassJob& job, SurfaceBuffers& buffers) {
    const VkBufferCopy values{0, 0, buffers.values.size};
    vkCmdCopyBuffer(job.commands, job.pixels->buffer, buffers.values.buffer, 1, &values);
    computeBarrier(job.commands);
    over(job, job.kernels->initial_bubbles, job.push.edge_count);
}

void recordSartSteps(const SurfacePassJob& job, SurfaceBuffers& buffers, uint32_t iterations) {
    const ReconstructionKernels& k = *job.kernels;
    const uint32_t pixels = job.push.width * job.push.height;
    const uint32_t sub_w = kSupersamplingFactor * job.push.width, sub_h = kSupersamplingFactor * job.push.height;
    // Setup: bounds, the stars' starting edges, the supersamples' triangles.
    over(job, k.value_bounds, pixels);
    fill(job.commands, buffers.star_start, kNone);
    computeBarrier(job.commands);
    over(job, k.star_starts, job.push.edge_count);
    job.triangle_pass(k.locate_samples);
    // SART's normalisers: ⟨φ, Dᵀ1⟩.
    fill(job.commands, buffers.residual, floatBits(1.0f));
    computeBarrier(job.commands);
    recordTranspose(job);
    recordProjection(job, buffers, 0);

    for (uint32_t i = 0; i < iterations; ++i) {
        over(job, k.evaluate_surface, sub_w * sub_h);
        over(job, k.degrade_y, sub_w * job.push.height);
        over(job, k.degrade_x, pixels);
        recordTranspose(job);
        recordProjection(job, buffers, 1);
    }
}

}  // namespace ddt
