// The consistent reconstruction's arrays (glsl/layout.h) and the quadratic surface on the
// mesh (core/image/reconstruct.h): vertex values plus one bubble per edge, 4·λp·λq·b_e on the edge's
// two triangles. Include after common.glsl.
layout(binding = kBindingHits, rgba32ui) uniform uimageBuffer hits;
layout(binding = kBindingSupersamples, rgba32f) uniform imageBuffer supersamples;
layout(binding = kBindingBetweenAxes, rgba32f) uniform imageBuffer between_axes;
layout(binding = kBindingResidual, rgba32f) uniform imageBuffer residual;
layout(binding = kBindingTaps, r32f) uniform readonly imageBuffer taps;
layout(binding = kBindingHalfEdgeValueSums, rgba32f) uniform imageBuffer half_edge_value_sums;
layout(binding = kBindingHalfEdgeBubbleSums, rgba32f) uniform imageBuffer half_edge_bubble_sums;
layout(binding = kBindingSurfaceValues, rgba32f) uniform imageBuffer surface_values;
layout(binding = kBindingValueLow, rgba32f) uniform imageBuffer value_low;
layout(binding = kBindingValueHigh, rgba32f) uniform imageBuffer value_high;
layout(binding = kBindingValueWeights, rgba32f) uniform imageBuffer value_weights;
layout(binding = kBindingBubbles, rgba32f) uniform imageBuffer bubbles;
layout(binding = kBindingBubbleWeights, rgba32f) uniform imageBuffer bubble_weights;
layout(binding = kBindingStarStart, r32ui) uniform uimageBuffer star_start;

// A triangle slot is 2e + side: the left (0) or right (1) triangle of its owning edge e, with
// core's listTriangles order: left (a, b, l), edges opposite them (bl, la, e); right
// (b, a, r), edges (ar, rb, e).
uvec3 slotVertices(uint slot) {
    const uvec4 v = verticesOf(slot >> 1);
    return (slot & 1) == 0 ? v.xyz : v.yxw;
}
uvec3 slotEdges(uint slot) {
    const uint e = slot >> 1;
    const uvec4 n = neighboursOf(e);
    return (slot & 1) == 0 ? uvec3(n.x, n.y, e) : uvec3(n.z, n.w, e);
}

// The half-edge of edge e on the side of its triangle that holds `vertex`.
uint halfEdgeFacing(uint e, uint vertex) { return 2 * e + (verticesOf(e).z == vertex ? 0 : 1); }

// The unclamped quadratic surface at barycentric weights l of a triangle with vertex values
// z and bubbles b on the edges opposite each vertex (as core's evaluate).
vec4 quadraticSurface(vec3 l, vec4 z0, vec4 z1, vec4 z2, vec4 b0, vec4 b1, vec4 b2) {
    return l.x * z0 + l.y * z1 + l.z * z2 + (4 * l.y * l.z) * b0 + (4 * l.z * l.x) * b1 + (4 * l.x * l.y) * b2;
}

// Premultiplied colour capped at alpha (the last channel), without a loop: loops count
// against lavapipe's per-invocation budget (kItemsPerInvocation).
vec4 colourAtMostAlpha(vec4 value) {
    if (push.has_alpha == 0) return value;
    const float a = value[push.channels - 1];
    return push.channels == 2 ? vec4(min(value.x, a), value.yzw) : vec4(min(value.xyz, vec3(a)), value.w);
}

// The supersampled grid: (3w) × (3h), row-major.
uint supersampledWidth() { return kSupersamplingFactor * push.width; }
uint supersampledHeight() { return kSupersamplingFactor * push.height; }
int supersampleAt(uint x, uint y) { return int(y * supersampledWidth() + x); }
