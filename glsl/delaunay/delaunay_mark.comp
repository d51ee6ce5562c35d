#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// A round's first step: mark every interior edge that is not locally Delaunay (the far vertex
// of its right triangle inside its left triangle's circumcircle, under the perturbed predicate
// of core/delaunay/predicates.h), and count them in the round's tally. Every edge is tested
// every round. Skipping the edges found locally Delaunay and unchanged since (a flag per edge,
// set by the flips) did not pay on lavapipe, where a round costs mostly its 3 × (edges)
// invocations: at 10^6 uniform points a round with almost no marks took 100 ms, one with
// 500 000, 155 ms; the flags took the flips from 6.7 s to 7.2 s (one run each, a busy machine).
#include "delaunay_common.glsl"
#include "in_circle.h"

void main() {
    const uint e = invocationEdge();
    if (e == kNone) return;
    const uvec4 v = verticesOf(e);
    const bool must_flip = v.z != kNone && v.w != kNone &&
                           inCirclePerturbed(positionOf(v.x), positionOf(v.y), positionOf(v.z), positionOf(v.w));
    imageStore(edge_states, int(e), uvec4(must_flip ? kEdgeMustFlip : kEdgeLocallyDelaunay));
    if (must_flip) imageAtomicAdd(tallies, int(2u * push.round), 1u);
}
