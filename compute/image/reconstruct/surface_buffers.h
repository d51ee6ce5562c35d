// The device arrays of the consistent reconstruction (bindings 19 on of glsl/layout.h). They
// start as placeholders, so that every binding is valid, and get their size when a
// reconstruction runs: a plain upscale never pays for them.
#pragma once

#include <cstdint>
#include <vector>

#include "buffer.h"
#include "context.h"

namespace ddt {

struct SurfaceBuffers {
    Buffer hits, supersamples, between_axes, residual, taps, half_edge_value_sums, half_edge_bubble_sums, values,
        value_low, value_high, value_weights, bubbles, bubble_weights, star_start;

    std::vector<Buffer*> all();
    // The buffer of a reconstruction binding of glsl/layout.h, nullptr for the other bindings.
    const Buffer* atBinding(uint32_t binding) const;
};

// Device bytes of the arrays for `vertices` input pixels and `edges` edges; and the most
// texel-buffer elements one of them has (the 3 × 3 supersamples).
uint64_t surfaceBufferBytes(uint64_t vertices, uint64_t edges);
uint64_t surfaceBufferLargestElements(uint64_t vertices, uint64_t edges);

SurfaceBuffers createSurfacePlaceholders(VulkanContext& context);
// Sized for a width × height input with `edges` edges and `tap_count` taps in all.
SurfaceBuffers createSurfaceBuffers(VulkanContext& context, uint32_t width, uint32_t height, uint32_t edges,
                                    uint32_t tap_count);
void destroySurfaceBuffers(VulkanContext& context, SurfaceBuffers& buffers);

}  // namespace ddt
