#version 460
#extension GL_GOOGLE_include_directive : require
// After the geometry (TetCosts::update's second half): the cost of each active tet — the new
// tets and, for face_scf, their face-neighbours, whose faces now border new tets. push.step
// kTetStepInit computes every slot's cost instead (0 for a free slot). The variance weight
// keeps no cache (its costs are recomputed where read): it computes only kTetStepTotals' chunk.
#include "tet_common.glsl"

void main() {
    const uint i = invocationIndex();
    if (push.step == kTetStepTotals) {
        const uint t = push.first + i;
        if (i >= kTetCostChunk || t >= control.slot_count) return;
        imageStore(tet_cost, int(i), inUse(t) ? doubleTexel(cachedCost(t)) : uvec4(0u));
        return;
    }
    if (push.face_scf == 0u) return;
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
