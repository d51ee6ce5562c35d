#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// A round's first step: mark every interior edge of the round's work list that is not locally
// Delaunay (the far vertex of its right triangle inside its left triangle's circumcircle, under
// the perturbed predicate of core/delaunay/predicates.h), and count them in the round's tally.
// The first round's list is every edge; a later round's holds the edges whose quadrilateral the
// last round changed (the flipped edges and their neighbours) and the marked edges that did not
// flip: every other edge was found locally Delaunay and is still. Lists, not a flag per edge
// tested by every invocation: on lavapipe a pass costs mostly its invocations (PLATFORM.md).
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
