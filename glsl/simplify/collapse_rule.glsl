// The legality and cost of a half-edge collapse as core/simplify/edge_collapse.h and
// vertex_quadrics.h define them, over the texel buffers of simplify_layout.h; the walks
// around a vertex follow core's forEachEdgeAt (the same edges; order does not matter here).
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "../layout.h"
#include "simplify_layout.h"
#include "quadric_value.h"
#include "../sederberg.h"

layout(local_size_x = kGroupSize) in;

layout(push_constant) uniform Push {
    SimplifyPush push;
};

// The mesh, the walks' starts and the quadrics change only in collapse_edges.comp.
layout(binding = kSimplifyBindingEdgeVertices, rgba32ui) uniform uimageBuffer edge_vertices;
layout(binding = kSimplifyBindingEdgeNeighbours, rgba32ui) uniform uimageBuffer edge_neighbours;
layout(binding = kSimplifyBindingVertexFirst, r32ui) uniform uimageBuffer vertex_first;
layout(binding = kSimplifyBindingValues, rgba32f) uniform readonly imageBuffer values;
layout(binding = kSimplifyBindingQuadrics, rg32ui) uniform uimageBuffer quadrics;

uvec4 verticesOf(uint e) { return imageLoad(edge_vertices, int(e)); }
uvec4 neighboursOf(uint e) { return imageLoad(edge_neighbours, int(e)); }
uint otherEnd(uvec4 v, uint p) { return v.x == p ? v.y : v.x; }

// core's turnAround: the edge after f around its endpoint v, counter-clockwise or clockwise.
uint turnAround(uint v, uint f, bool counter_clockwise) {
    const uvec4 n = neighboursOf(f);
    if (verticesOf(f).x == v) return counter_clockwise ? n.y : n.z;
    return counter_clockwise ? n.w : n.x;
}

// A walk over the edges at a vertex: `for (Walk w = beginWalk(v); w.f != kNone; advance(w))`
// visits them counter-clockwise from the vertex's first edge, then, where that meets the
// hull, clockwise from it.
struct Walk {
    uint v, start, f;
    bool forward;
};
Walk beginWalk(uint v) {
    const uint start = imageLoad(vertex_first, int(v)).x;
    return Walk(v, start, start, true);
}
void advance(inout Walk w) {
    uint next = turnAround(w.v, w.f, w.forward);
    if (w.forward) {
        if (next == w.start) next = kNone;
        else if (next == kNone) {
            w.forward = false;
            next = turnAround(w.v, w.start, false);
        }
    }
    w.f = next;
}

// 1 for the vertices whose edges the last round's collapses changed (collapse_edges.comp).
layout(binding = kSimplifyBindingChanged, r32ui) uniform uimageBuffer changed;

layout(binding = kSimplifyBindingListed, r32ui) uniform uimageBuffer listed;

// The edge this invocation works on (push.listed: the listed one), or kNone past the end.
uint invocationEdge() {
    const uint i = push.first_edge + gl_GlobalInvocationID.x;
    if (i >= push.edge_count) return kNone;
    return push.listed != 0u ? imageLoad(listed, int(i)).x : i;
}

// The rectangle's sides v lies on: bit 0 x = 0, 1 x = w − 1, 2 y = 0, 3 y = h − 1.
uint sidesOf(uint v) {
    const uint x = v % push.width, y = v / push.width;
    return uint(x == 0u) | uint(x == push.width - 1u) << 1 | uint(y == 0u) << 2 | uint(y == push.height - 1u) << 3;
}

// Whether triangle (p, q, r) at `from`, with `to` in its place, is not positive any more (one
// of the collapsing edge's own triangles, which go, never is).
bool folds(uint p, uint q, uint r, uint from, uint to) {
    if (p == to || q == to || r == to) return false;
    p = p == from ? to : p;
    q = q == from ? to : q;
    r = r == from ? to : r;
    return orientation(p, q, r, push.width) <= 0.0lf;
}

// core's canCollapse for edge e, in two parts: what holds for both directions (the valence
// bound and the link condition), then what depends on the direction.
bool eitherWayLegal(uint e) {
    const uvec4 ev = verticesOf(e);
    // b's neighbours, listed once (at most kMaxEdgesAtFrom where the valence bound holds), so
    // that the link condition's pairs compare registers rather than walk b's edges again.
    uint at_b[kMaxEdgesAtFrom];
    uint b_count = 0u, valence = 0u;
    for (Walk w = beginWalk(ev.y); w.f != kNone; advance(w)) {
        if (b_count < kMaxEdgesAtFrom) at_b[b_count] = otherEnd(verticesOf(w.f), ev.y);
        ++b_count;
    }
    for (Walk w = beginWalk(ev.x); w.f != kNone; advance(w)) ++valence;
    valence += b_count;
    if (valence - 2u - uint(ev.z != kNone) - uint(ev.w != kNone) > kCollapseValenceBound) return false;
    // Link condition: the common neighbours of a and b are e's adjacent vertices.
    uint shared_neighbours = 0u;
    for (Walk w = beginWalk(ev.x); w.f != kNone; advance(w)) {
        const uint x = otherEnd(verticesOf(w.f), ev.x);
        if (x == ev.y) continue;
        for (uint i = 0u; i < b_count; ++i) {
            if (at_b[i] != x) continue;
            if (x != ev.z && x != ev.w) return false;
            ++shared_neighbours;
        }
    }
    return shared_neighbours == uint(ev.z != kNone) + uint(ev.w != kNone);
}

// The rest of core's canCollapse, `from` e's endpoint b (b_into_a) or a: the rectangle kept,
// no fold-over.
bool directionLegal(uint e, bool b_into_a) {
    const uvec4 ev = verticesOf(e);
    const uint from = b_into_a ? ev.y : ev.x, to = b_into_a ? ev.x : ev.y;
    const uint from_sides = sidesOf(from);
    if (bitCount(from_sides) >= 2) return false;                           // a corner
    if (from_sides != 0u && ev.z != kNone && ev.w != kNone) return false;  // a border vertex leaves its side
    for (Walk w = beginWalk(from); w.f != kNone; advance(w)) {
        if (w.f == e) continue;
        const uvec4 fv = verticesOf(w.f);
        if (fv.z != kNone && folds(fv.x, fv.y, fv.z, from, to)) return false;
        if (fv.w != kNone && folds(fv.y, fv.x, fv.w, from, to)) return false;
    }
    return true;
}

double quadricWord(uint v, uint k) { return packDouble2x32(imageLoad(quadrics, int(v * kQuadricDoubles + k)).xy); }

// The sum of two vertices' quadrics, the entries that 2 + push.channels coordinates use (the
// rest stay 0): both directions of a collapse cost this sum, since addition commutes.
struct QuadricSum {
    double a[kQuadricUpperSize];
    double b[kMaxQuadricDimensions];
    double c;
    double area;
};
QuadricSum quadricSum(uint p, uint q) {
    QuadricSum sum;
    const uint n = 2u + push.channels;
    for (uint i = 0u; i < kMaxQuadricDimensions; ++i) {
        for (uint j = i; j < kMaxQuadricDimensions; ++j) {
            const uint k = quadricIndex(i, j);
            sum.a[k] = j < n ? quadricWord(p, k) + quadricWord(q, k) : 0.0lf;
        }
        sum.b[i] = i < n ? quadricWord(p, kQuadricUpperSize + i) + quadricWord(q, kQuadricUpperSize + i) : 0.0lf;
    }
    sum.c = quadricWord(p, kQuadricUpperSize + kMaxQuadricDimensions) +
            quadricWord(q, kQuadricUpperSize + kMaxQuadricDimensions);
    sum.area = quadricWord(p, kQuadricUpperSize + kMaxQuadricDimensions + 1u) +
               quadricWord(q, kQuadricUpperSize + kMaxQuadricDimensions + 1u);
    return sum;
}

// core's collapseCost: the two quadrics' sum at the point of the vertex that stays (its
// position times kPositionWeight = 4, then its channels).
double collapseCost(QuadricSum sum, uint to) {
    double point[kMaxQuadricDimensions];
    for (uint k = 0u; k < kMaxQuadricDimensions; ++k) point[k] = 0.0lf;
    point[0] = 4.0lf * double(to % push.width);
    point[1] = 4.0lf * double(to / push.width);
    const vec4 value = imageLoad(values, int(to));
    for (uint k = 0u; k < push.channels; ++k) point[2u + k] = double(value[k]);
    return quadricValue(sum.a, sum.b, sum.c, point, 2u + push.channels);
}
