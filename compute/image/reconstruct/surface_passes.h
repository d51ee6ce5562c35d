// The consistent reconstruction (core/image/reconstruct.h) recorded as device passes: the setup
// (initial surface, bounds, the supersamples' triangles, SART's weights), then every SART
// step: evaluate, degrade, residual, transpose, project onto the basis, update. Every sum is
// a gather in an order fixed by the mesh and the grid, so the result does not depend on
// timing or thread count.
#pragma once

#include <functional>

#include "commands.h"
#include "image_kernels.h"
#include "surface_buffers.h"

namespace ddt {

struct SurfacePassJob {
    VkCommandBuffer commands = VK_NULL_HANDLE;
    const ReconstructionKernels* kernels = nullptr;
    KernelBindings bindings;
    PushConstants push{};  // the job's scalars, the taps' radii and integer_samples set
    const Buffer* pixels = nullptr;  // the input, one rgba32f texel per pixel
    // Records `kernel` over every triangle of the supersampled grid, in parts (the
    // per-triangle passes of glsl/image/reconstruct/triangle_pass.glsl).
    std::function<void(VkPipeline kernel)> triangle_pass;
};

// Records the starting surface only (iterations 0, or an identity degradation).
void recordInitialSurface(const SurfacePassJob& job, SurfaceBuffers& buffers);
// Records the SART iterations on top of recordInitialSurface's surface.
void recordSartSteps(const SurfacePassJob& job, SurfaceBuffers& buffers, uint32_t iterations);

}  // namespace ddt
