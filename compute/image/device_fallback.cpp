// The convolution fallback on the device (core/image/convolution_fallback.h): the surface's
// weights made once from the prepared pixels (glsl/image/fallback/: the gradient energy, then
// the Gaussian along x and along y with the mapping to weights), and each rendered band
// blended towards Lanczos3 of the input before it is read back (fallback_blend.comp).
#include <cassert>

#include "convolution_fallback.h"
#include "fallback/fallback_constants.h"
#include "vulkan_backend_state.h"

namespace ddt {

static_assert(kFallbackWeightFlat == kWeightFlat && kFallbackWeightEdge == kWeightEdge &&
                  kFallbackLogFlat == kLogFlat && kFallbackLogEdge == kLogEdge,
              "glsl/image/fallback/fallback_constants.h follows core/image/convolution_fallback.h");
// A sample's reach: the weights' bilinear cell (1), Sobel (1) and the Gaussian; Lanczos3 reaches less.
static_assert(2 + kFallbackGaussianRadius == kFallbackReach && kFallbackTaps / 2 <= kFallbackReach,
              "core/image/convolution_fallback.h's reach covers the kernels'");

void VulkanBackend::addFallback(float grain_share) {
    State& s = *state_;
    assert(s.explicit_positions.empty());  // the grid's mesh: vertex v is pixel v of the prepared image
    VulkanContext& c = *s.context;
    const uint32_t pixels = s.vertex_count;
    destroyBuffer(c, s.fallback_weights);
    destroyBuffer(c, s.fallback_across);
    // rgba32f: the structure tensor's three products per pixel while the weights are made.
    s.fallback_weights = createBuffer(c, uint64_t(pixels) * 16, Placement::Device, VK_FORMAT_R32G32B32A32_SFLOAT);
    s.fallback_across = createBuffer(c, uint64_t(pixels) * 16, Placement::Device, VK_FORMAT_R32G32B32A32_SFLOAT);
    s.writeDescriptors();
    {
        CommandBatch batch(c);
        const FallbackKernels& k = s.kernels.fallback;
        PushConstants p = s.push();
        p.grain_share = grain_share;
        for (VkPipeline kernel : {k.energy, k.smooth_x, k.weights})
            dispatch(batch.buffer(), kernel, s.bindings(), p, groupsFor(pixels));
        batch.submitAndWait();
    }
    // The tensor smoothed along x served only to make the weights: back to a placeholder.
    destroyBuffer(c, s.fallback_across);
    s.fallback_across = createBuffer(c, 16, Placement::Device, VK_FORMAT_R32G32B32A32_SFLOAT);
    s.writeDescriptors();
    s.fallback = true;
}

void VulkanBackend::State::blendBand(const RenderWindow& window, uint32_t y_begin, uint32_t y_end) {
    PushConstants p = windowPush(window);
    p.first_row = y_begin;
    p.row_count = y_end - y_begin;
    p.integer_samples = boundedToUnit(image->sample_type) ? 1 : 0;
    CommandBatch batch(*context);
    dispatch(batch.buffer(), kernels.fallback.blend, bindings(), p, groupsFor(p.row_count * p.band_width));
    batch.submitAndWait();
}

}  // namespace ddt
