#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// A round's second step: a marked edge flips now if its priority (flipPriority) is below that
// of every marked edge of its two triangles, its four neighbours. No two chosen edges then share
// a triangle, so their flips touch disjoint records but for the two sides of a shared
// neighbour (delaunay_flip.comp). The marked edge of least priority overall always wins: every
// round with a mark flips something. A marked edge that loses goes on the next round's list.
// Neighbours off this round's list keep the state their last marks gave (still true: their
// quadrilaterals have not changed since); a neighbour chosen already in this dispatch
// (kEdgeFlipsNow) was marked all the same.
#include "delaunay_common.glsl"

void main() {
    const uint e = invocationEdge();
    if (e == kNone) return;
    if (stateOf(e) == kEdgeLocallyDelaunay) return;
    const uvec4 n = neighboursOf(e);
    const uint priority = flipPriority(e, push.round);
    for (uint i = 0u; i < 4u; ++i) {
        const uint g = n[i];
        if (stateOf(g) != kEdgeLocallyDelaunay && flipPriority(g, push.round) < priority) {
            queueForNextRound(e);
            return;
        }
    }
    imageStore(edge_states, int(e), uvec4(kEdgeFlipsNow));
    imageAtomicAdd(tallies, int(2u * push.round + 1u), 1u);
}
