#version 460
#extension GL_GOOGLE_include_directive : require
// Step (a) of a round (core/volume/tet_parallel.h): each tet of the evaluation list proposes its
// best owned flip worth applying, appended to the candidate list as its owner, its site and its
// key's high word (the tie word is a function of the owner); invocations past the evaluation
// list take the carried candidates of the last round into the list as they are, but where their
// owners are being evaluated anew (their state's evaluation bit, which tet_select clears after
// this step). The list's order does not matter: every later step is order-independent.
#include "tet_plan.glsl"

void main() {
    const uint i = invocationIndex();
    if (i >= control.eval_count) {
        const uint j = i - control.eval_count;
        if (j >= control.carry_count) return;
        const uvec2 entry = imageLoad(carried_list, int(j)).xy;
        const uint owner = entry.x & (kTetMaxSlots - 1u);
        if ((imageLoad(tet_state, int(owner)).x & kTetStateEval) != 0u) return;
        imageStore(candidate_list, int(atomicAdd(control.candidate_count, 1u)), uvec4(entry.x, entry.y & ~kTetAccepted, 0u, 0u));
        return;
    }
    const uint t = imageLoad(eval_list, int(i)).x;
    if (!inUse(t)) {  // freed since it was listed
        atomicAdd(control.skipped, 1u);
        return;
    }
    uint site;
    double gain;
    if (!bestOwnedFlip(t, site, gain)) return;
    const uint entry = atomicAdd(control.candidate_count, 1u);
    imageStore(candidate_list, int(entry), uvec4(t | site << kTetSiteShift, unpackDouble2x32(gain).y, 0u, 0u));
}
