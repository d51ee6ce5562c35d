#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// A round's second step: a marked edge flips now if its priority (flipPriority) is below that
// of every marked edge of its two triangles, its four neighbours. No two chosen edges then share
// a triangle, so their flips touch disjoint records but for the two sides of a shared
// neighbour (delaunay_flip.comp). The marked edge of least priority overall always wins: every
// round with a mark flips something. Reads states as 0 or not: a neighbour chosen already in
// this dispatch (kEdgeFlipsNow) was marked all the same.
#include "delaunay_common.glsl"

void main() {
    const uint e = invocationEdge();
    if (e == kNone) return;
    if (imageLoad(edge_states, int(e)).x == kEdgeLocallyDelaunay) return;
    const uvec4 n = neighboursOf(e);
    const uint priority = flipPriority(e, push.round);
    for (uint i = 0u; i < 4u; ++i) {
        const uint g = n[i];
        if (imageLoad(edge_states, int(g)).x != kEdgeLocallyDelaunay && flipPriority(g, push.round) < priority) return;
    }
    imageStore(edge_states, int(e), uvec4(kEdgeFlipsNow));
    imageAtomicAdd(tallies, int(2u * push.round + 1u), 1u);
}
