#version 460
#extension GL_GOOGLE_include_directive : require
// Step (d) of core/volume/tet_parallel.h, run at the start of a round: each active tet (a new
// tet of the last round or, for face_scf, a face-neighbour of one) lists in the evaluation
// list the owner of each of its flippable, not all-flat sites (core's forEachSiteOwner); the
// state bit keeps each owner listed once. The last round's unaccepted candidates whose read
// sets a flip touched are listed already (tet_select.comp's judge step). In the first round the
// active tets are those that are not flat (tet_refresh.comp's kTetStepInit).
#include "tet_plan.glsl"

void main() {
    const uint i = invocationIndex();
    if (i >= control.active_count) return;
    const uint t = imageLoad(active_list, int(i)).x;
    imageAtomicAnd(tet_state, int(t), ~kTetStateActive);
    const uvec4 tv = verticesOf(t), tn = neighboursOf(t);
    const bool t_flat = isFlat(t);
    for (uint f = 0u; f < 4u; ++f) {
        const uint n = tn[f];
        if (n != kNoTet && !(t_flat && isFlat(n))) listEval(min(t, n));
    }
    for (uint k = 0u; k < 6u; ++k) {
        if (edgeRingOf(t, tv, kEdges[k].x, kEdges[k].y) && flippableRing() && !ringIsFlat()) listEval(ringOwner());
    }
}
