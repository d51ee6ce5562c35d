// Shared by every kernel: the bindings, the push constants, and mesh navigation over the
// edge arrays in the words of core/image/mesh.h (a, b, l, r; neighbours bl, la, ar, rb).
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "content_cost.h"
#include "layout.h"
#include "sederberg.h"

layout(local_size_x = kGroupSize) in;

// The cost the optimisation lowers: kCostSederberg, kCostVariance or kCostFaceScf
// (glsl/image/content_cost.h; compute/image/image_kernels.h sets it from VulkanOptions::cost).
layout(constant_id = 2) const uint kCost = kCostSederberg;
// Whether the mesh has explicit vertex positions (core/image/mesh.h), which the cost formulas then
// read from `positions` (glsl/image/sederberg.h's Places); false: every vertex at its pixel centre,
// computed from its id, and the reads compile away (compute/image/image_kernels.h sets it).
layout(constant_id = 3) const bool kPositioned = false;

layout(push_constant) uniform Push {
    PushConstants push;
};

layout(binding = kBindingEdgeVertices, rgba32ui) uniform uimageBuffer edge_vertices;
layout(binding = kBindingEdgeNeighbours, rgba32ui) uniform uimageBuffer edge_neighbours;
layout(binding = kBindingLuma, r32f) uniform readonly imageBuffer luma;
layout(binding = kBindingAlpha, r32f) uniform readonly imageBuffer alpha;
layout(binding = kBindingGain, rg32ui) uniform uimageBuffer gains;
layout(binding = kBindingStatus0, r32ui) uniform uimageBuffer status0;
layout(binding = kBindingStatus1, r32ui) uniform uimageBuffer status1;
layout(binding = kBindingMark, r32ui) uniform uimageBuffer marks;
layout(binding = kBindingActiveList0, r32ui) uniform uimageBuffer active_list0;
layout(binding = kBindingActiveList1, r32ui) uniform uimageBuffer active_list1;
layout(binding = kBindingCandidateList, r32ui) uniform uimageBuffer candidate_list;
layout(binding = kBindingAcceptedList, r32ui) uniform uimageBuffer accepted_list;
layout(binding = kBindingRoundList0, r32ui) uniform uimageBuffer round_list0;
layout(binding = kBindingRoundList1, r32ui) uniform uimageBuffer round_list1;
layout(binding = kBindingPixels, rgba32f) uniform readonly imageBuffer pixels;
// Written by render.comp, read and rewritten by fallback/fallback_blend.comp.
layout(binding = kBindingBand, rgba32f) uniform imageBuffer band;
layout(binding = kBindingRowSpans, r32ui) uniform uimageBuffer row_spans;
layout(binding = kBindingPartialSums, rg32ui) uniform writeonly uimageBuffer partial_sums;
layout(binding = kBindingControl, std430) buffer ControlBlock {
    Control control;
};
layout(binding = kBindingArgs, std430) buffer ArgsBlock {
    uvec4 args[kArgsCount];
};
layout(binding = kBindingPositions, rg32i) uniform readonly iimageBuffer positions;

// glsl/image/sederberg.h's places of the vertices, and the explicit positions it reads.
Position vertexPosition(uint v) {
    const ivec2 p = imageLoad(positions, int(v)).xy;
    return Position(p.x, p.y);
}
Places places() { return Places(push.width, kPositioned); }

// Invocations of the whole dispatch, for loops over ranges larger than one dispatch.
uint invocationStride() { return gl_NumWorkGroups.x * kGroupSize; }

uvec4 verticesOf(uint e) { return imageLoad(edge_vertices, int(e)); }
uvec4 neighboursOf(uint e) { return imageLoad(edge_neighbours, int(e)); }

// Texel buffers cannot be indexed dynamically on every device: parity picks the binding.
uint statusOf(uint parity, uint e) { return parity == 0 ? imageLoad(status0, int(e)).x : imageLoad(status1, int(e)).x; }
void setStatus(uint parity, uint e, uint status) {
    if (parity == 0) imageStore(status0, int(e), uvec4(status));
    else imageStore(status1, int(e), uvec4(status));
}

// An edge's mark (binding marks) when the flip step lists it for iteration i: an unflipped
// candidate whose stencil no flip changed keeps its gain, and is listed as kept; an edge in a
// flip's closed ROI must be evaluated again. The larger mark wins, and either lists the edge once.
uint keptMark(uint iteration) { return 2 * iteration; }
uint retestMark(uint iteration) { return 2 * iteration + 1; }

// A double travels as its two 32-bit halves.
double gainOf(uint e) { return packDouble2x32(imageLoad(gains, int(e)).xy); }
void setGain(uint e, double gain) { imageStore(gains, int(e), uvec4(unpackDouble2x32(gain), 0u, 0u)); }

// Far vertex of neighbour edge n as seen from the triangle whose third vertex is `near`.
uint farVertex(uint n, uint near) {
    if (n == kNone) return kNone;
    uvec4 v = verticesOf(n);
    return v.z == near ? v.w : v.z;
}

// The stencil of e's flip. Variance's gain reads only a, b, l, r: its far vertices are left
// kNone, which saves reading the four neighbours' records.
FlipStencil flipStencilOf(uint e) {
    uvec4 v = verticesOf(e);
    FlipStencil s;
    s.a = v.x;
    s.b = v.y;
    s.l = v.z;
    s.r = v.w;
    s.far_bl = kNone;
    s.far_la = kNone;
    s.far_ar = kNone;
    s.far_rb = kNone;
    if (kCost != kCostVariance) {
        uvec4 n = neighboursOf(e);
        s.far_bl = farVertex(n.x, v.x);
        s.far_la = farVertex(n.y, v.y);
        s.far_ar = farVertex(n.z, v.y);
        s.far_rb = farVertex(n.w, v.x);
    }
    return s;
}

float valueAt(bool alpha_channel, uint vertex) {
    if (vertex == kNone) return 0.0;
    return alpha_channel ? imageLoad(alpha, int(vertex)).x : imageLoad(luma, int(vertex)).x;
}

StencilValues stencilValues(bool alpha_channel, FlipStencil s) {
    StencilValues z;
    z.a = valueAt(alpha_channel, s.a);
    z.b = valueAt(alpha_channel, s.b);
    z.l = valueAt(alpha_channel, s.l);
    z.r = valueAt(alpha_channel, s.r);
    z.far_bl = valueAt(alpha_channel, s.far_bl);
    z.far_la = valueAt(alpha_channel, s.far_la);
    z.far_ar = valueAt(alpha_channel, s.far_ar);
    z.far_rb = valueAt(alpha_channel, s.far_rb);
    return z;
}

// Gain of flipping e under kCost, as core's flipGainOf; a non-convex quadrilateral returns -1,
// which is below any threshold (core returns -infinity, which GLSL cannot spell).
double flipGainOf(uint e) {
    FlipStencil s = flipStencilOf(e);
    if (!flipIsConvex(s, places())) return -1.0lf;
    precise double gain = costFlipGain(kCost, s, stencilValues(false, s), places());
    if (push.has_alpha != 0) gain += costFlipGain(kCost, s, stencilValues(true, s), places());
    return gain;
}

// Sederberg's or face-SCF's share of an interior edge, for one channel.
double channelEdgeCost(bool alpha_channel, uvec4 v) {
    Gradient left = planeGradient(v.x, v.y, v.z, valueAt(alpha_channel, v.x), valueAt(alpha_channel, v.y),
                                  valueAt(alpha_channel, v.z), places());
    Gradient right = planeGradient(v.y, v.x, v.w, valueAt(alpha_channel, v.y), valueAt(alpha_channel, v.x),
                                   valueAt(alpha_channel, v.w), places());
    return pairCost(left, right, kCost == kCostFaceScf);
}

// Variance's share of an edge, for one channel: the triangles it reports, left then right.
double channelVarianceShare(bool alpha_channel, uvec4 v, bool left, bool right) {
    const float za = valueAt(alpha_channel, v.x), zb = valueAt(alpha_channel, v.y);
    precise double share = 0.0lf;
    if (left) share += varianceCost(v.x, v.y, v.z, za, zb, valueAt(alpha_channel, v.z), places());
    if (right) share += varianceCost(v.y, v.x, v.w, zb, za, valueAt(alpha_channel, v.w), places());
    return share;
}

// Edge e's share of the mesh cost under kCost, as core's edgeCost: Sederberg's and face-SCF's
// are 0 for a boundary edge; variance's is the cost of the triangles of whose edges e has the
// lowest id (core's forEachTriangle), so that every triangle counts once.
double edgeCostOf(uint e) {
    uvec4 v = verticesOf(e);
    if (kCost == kCostVariance) {
        const uvec4 n = neighboursOf(e);
        const bool left = v.z != kNone && e < n.x && e < n.y, right = v.w != kNone && e < n.z && e < n.w;
        precise double share = channelVarianceShare(false, v, left, right);
        if (push.has_alpha != 0) share += channelVarianceShare(true, v, left, right);
        return share;
    }
    if (v.z == kNone || v.w == kNone) return 0.0lf;
    precise double cost = channelEdgeCost(false, v);
    if (push.has_alpha != 0) cost += channelEdgeCost(true, v);
    return cost;
}
