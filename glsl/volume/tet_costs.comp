#version 460
#extension GL_GOOGLE_include_directive : require
// After the geometry (TetCosts::update's second half): the cost of each active tet — the new
// tets and, for face_scf, their face-neighbours, whose faces now border new tets. push.step
// kTetStepInit computes every slot's cost instead (0 for a free slot).
#include "tet_common.glsl"

void main() {
    const uint i = invocationIndex();
    uint t;
    if (push.step == kTetStepInit) {
        if (i >= control.slot_count) return;
        t = i;
        if (!inUse(t)) {
            imageStore(tet_cost, int(t), uvec4(0u));
            return;
        }
    } else {
        if (i >= control.active_count) return;
        t = imageLoad(active_list, int(i)).x;
    }
    imageStore(tet_cost, int(t), doubleTexel(cachedCost(t)));
}
