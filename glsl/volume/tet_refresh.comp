#version 460
#extension GL_GOOGLE_include_directive : require
// After the flips (TetCosts::update's first half): each new tet's flatness and (for
// face_scf) gradient from its record, and, for face_scf, its face-neighbours listed as active
// (their costs read its gradient; tet_lawson's candidate list). Invocation j < three_twos also
// pushes the j-th freed slot onto the free slots. push.step kTetStepInit refreshes every slot
// in use instead (the first round's cache) and lists those that are not flat as active (the
// first round's active tets, core/volume/tet_parallel.h).
#include "tet_common.glsl"

void refreshGeometry(uint t, uvec4 v) {
    if (flatTet(v)) imageAtomicOr(tet_state, int(t), kTetStateFlat);
    else imageAtomicAnd(tet_state, int(t), ~kTetStateFlat);
    if (push.face_scf != 0u) {
        const dvec3 g = gradientOfTet(v);
        for (uint a = 0u; a < 3u; ++a) imageStore(tet_gradient, int(3u * t + a), doubleTexel(g[a]));
    }
}

void main() {
    const uint i = invocationIndex();
    if (push.step == kTetStepInit) {
        if (i >= control.slot_count) return;
        const uvec4 v = verticesOf(i);
        if (v.x == kNoTet) return;
        refreshGeometry(i, v);
        if (!flatTet(v)) listActive(i);
        return;
    }
    if (i < control.three_twos) {
        const uint left = control.base_free - min(control.two_threes, control.base_free);
        imageStore(free_slots, int(left + i), imageLoad(freed_slots, int(i)));
    }
    if (i >= control.new_count) return;
    const uint t = imageLoad(active_list, int(i)).x;
    refreshGeometry(t, verticesOf(t));
    if (push.face_scf == 0u) return;
    const uvec4 n = neighboursOf(t);
    for (uint f = 0u; f < 4u; ++f)
        if (n[f] != kNoTet) listActive(n[f]);
}
