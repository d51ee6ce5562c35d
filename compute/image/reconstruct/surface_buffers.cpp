#include "surface_buffers.h"

#include <algorithm>

#include "layout.h"

namespace ddt {

namespace {

const uint64_t kSupersamples = kSupersamplingFactor * kSupersamplingFactor;  // per input pixel

}  // namespace

std::vector<Buffer*> SurfaceBuffers::all() {
    return {&hits,   &supersamples, &between_axes, &residual,      &taps,    &half_edge_value_sums, &half_edge_bubble_sums,
            &values, &value_low,    &value_high,   &value_weights, &bubbles, &bubble_weights,       &star_start};
}

const Buffer* SurfaceBuffers::atBinding(uint32_t binding) const {
    switch (binding) {
        case kBindingHits: return &hits;
        case kBindingSupersamples: return &supersamples;
        case kBindingBetweenAxes: return &between_axes;
        case kBindingResidual: return &residual;
        case kBindingTaps: return &taps;
        case kBindingHalfEdgeValueSums: return &half_edge_value_sums;
        case kBindingHalfEdgeBubbleSums: return &half_edge_bubble_sums;
        case kBindingSurfaceValues: return &values;
        case kBindingValueLow: return &value_low;
        case kBindingValueHigh: return &value_high;
        case kBindingValueWeights: return &value_weights;
        case kBindingBubbles: return &bubbles;
        case kBindingBubbleWeights: return &bubble_weights;
        case kBindingStarStart: return &star_start;
        default: return nullptr;
    }
}

// Per pixel: the hits and the supersamples (16 bytes each, 9 of them), the intermediate
// between the axes (3), the residual, values, two bounds and weights (16 each), the star's
// start (4). Per edge: two half-edges of two sums, the bubble and its weight (16 each).
uint64_t surfaceBufferBytes(uint64_t vertices, uint64_t edges) {
    return vertices * (16 * (2 * kSupersamples + kSupersamplingFactor + 5) + 4) + edges * 16 * (2 * 2 + 2);
}

uint64_t surfaceBufferLargestElements(uint64_t vertices, uint64_t edges) {
    return std::max(vertices * kSupersamples, 2 * edges);
}

SurfaceBuffers createSurfacePlaceholders(VulkanContext& context) {
    SurfaceBuffers buffers;
    for (Buffer* buffer : buffers.all())
        *buffer = createBuffer(context, 16, Placement::Device,
                               buffer == &buffers.hits         ? VK_FORMAT_R32G32B32A32_UINT
                               : buffer == &buffers.taps       ? VK_FORMAT_R32_SFLOAT
                               : buffer == &buffers.star_start ? VK_FORMAT_R32_UINT
                                                               : VK_FORMAT_R32G32B32A32_SFLOAT);
    return buffers;
}

SurfaceBuffers createSurfaceBuffers(VulkanContext& c, uint32_t width, uint32_t height, uint32_t edges,
                                    uint32_t tap_count) {
    const uint64_t pixels = uint64_t(width) * height, texel = 16;
    const VkFormat rgba = VK_FORMAT_R32G32B32A32_SFLOAT;
    const Placement device = Placement::Device;
    SurfaceBuffers b;
    b.hits = createBuffer(c, pixels * kSupersamples * texel, device, VK_FORMAT_R32G32B32A32_UINT);
    b.supersamples = createBuffer(c, pixels * kSupersamples * texel, device, rgba);
    b.between_axes = createBuffer(c, pixels * kSupersamplingFactor * texel, device, rgba);
    b.residual = createBuffer(c, pixels * texel, device, rgba);
    b.taps = createBuffer(c, uint64_t(tap_count) * 4, device, VK_FORMAT_R32_SFLOAT);
    b.half_edge_value_sums = createBuffer(c, 2 * uint64_t(edges) * texel, device, rgba);
    b.half_edge_bubble_sums = createBuffer(c, 2 * uint64_t(edges) * texel, device, rgba);
    b.values = createBuffer(c, pixels * texel, device, rgba);
    b.value_low = createBuffer(c, pixels * texel, device, rgba);
    b.value_high = createBuffer(c, pixels * texel, device, rgba);
    b.value_weights = createBuffer(c, pixels * texel, device, rgba);
    b.bubbles = createBuffer(c, uint64_t(edges) * texel, device, rgba);
    b.bubble_weights = createBuffer(c, uint64_t(edges) * texel, device, rgba);
    b.star_start = createBuffer(c, pixels * 4, device, VK_FORMAT_R32_UINT);
    return b;
}

void destroySurfaceBuffers(VulkanContext& context, SurfaceBuffers& buffers) {
    for (Buffer* buffer : buffers.all()) destroyBuffer(context, *buffer);
}

}  // namespace ddt
