// Shared by every kernel: extensions, the push constants, and mesh navigation over the
// edge arrays in the words of core/mesh.h (a, b, l, r; neighbours bl, la, ar, rb).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "layout.h"
#include "sederberg.h"

layout(local_size_x = kGroupSize) in;

layout(push_constant) uniform Push {
    PushConstants push;
};

// Every kernel starts with loadParams(). The hot addresses and sizes are copied into
// private variables once: lavapipe re-reads every `params.x` from memory, lane by lane,
// since stores elsewhere might alias it, and those reloads dominated the kernels' time.
DeviceParams params;
UVec4Array edge_vertices;
UVec4Array edge_neighbours;
FloatArray luma;
FloatArray alpha;
uint width;
bool has_alpha;

void loadParams() {
    params = push.params;
    edge_vertices = params.edge_vertices;
    edge_neighbours = params.edge_neighbours;
    luma = params.luma;
    alpha = params.alpha;
    width = params.width;
    has_alpha = params.has_alpha != 0;
}

// Invocations of the whole dispatch, for loops over ranges larger than one dispatch.
uint invocationStride() { return gl_NumWorkGroups.x * kGroupSize; }

uvec4 verticesOf(uint e) { return edge_vertices.at[e]; }
uvec4 neighboursOf(uint e) { return edge_neighbours.at[e]; }

// Far vertex of neighbour edge n as seen from the triangle whose third vertex is `near`.
uint farVertex(uint n, uint near) {
    if (n == kNone) return kNone;
    uvec4 v = verticesOf(n);
    return v.z == near ? v.w : v.z;
}

FlipStencil flipStencilOf(uint e) {
    uvec4 v = verticesOf(e);
    uvec4 n = neighboursOf(e);
    FlipStencil s;
    s.a = v.x;
    s.b = v.y;
    s.l = v.z;
    s.r = v.w;
    s.far_bl = farVertex(n.x, v.x);
    s.far_la = farVertex(n.y, v.y);
    s.far_ar = farVertex(n.z, v.y);
    s.far_rb = farVertex(n.w, v.x);
    return s;
}

float valueAt(FloatArray channel, uint vertex) { return vertex == kNone ? 0.0 : channel.at[vertex]; }

StencilValues stencilValues(FloatArray channel, FlipStencil s) {
    StencilValues z;
    z.a = valueAt(channel, s.a);
    z.b = valueAt(channel, s.b);
    z.l = valueAt(channel, s.l);
    z.r = valueAt(channel, s.r);
    z.far_bl = valueAt(channel, s.far_bl);
    z.far_la = valueAt(channel, s.far_la);
    z.far_ar = valueAt(channel, s.far_ar);
    z.far_rb = valueAt(channel, s.far_rb);
    return z;
}

// Gain of flipping e, as core's flipGainOf; a non-convex quadrilateral returns -1, which is
// below any threshold (core returns -infinity, which GLSL cannot spell).
double flipGainOf(uint e) {
    FlipStencil s = flipStencilOf(e);
    if (!flipIsConvex(s, width)) return -1.0lf;
    precise double gain = flipGain(s, stencilValues(luma, s), width);
    if (has_alpha) gain += flipGain(s, stencilValues(alpha, s), width);
    return gain;
}

double channelEdgeCost(FloatArray z, uvec4 v) {
    Gradient left = planeGradient(v.x, v.y, v.z, z.at[v.x], z.at[v.y], z.at[v.z], width);
    Gradient right = planeGradient(v.y, v.x, v.w, z.at[v.y], z.at[v.x], z.at[v.w], width);
    return sederbergCost(left, right);
}

// Cost of edge e, as core's edgeCost (0 for a boundary edge).
double edgeCostOf(uint e) {
    uvec4 v = verticesOf(e);
    if (v.z == kNone || v.w == kNone) return 0.0lf;
    precise double cost = channelEdgeCost(luma, v);
    if (has_alpha) cost += channelEdgeCost(alpha, v);
    return cost;
}

// Workgroups for `count` items, at most the device's max_groups (the kernels loop).
uint groupsFor(uint count) { return min((count + kGroupSize - 1) / kGroupSize, params.max_groups); }
