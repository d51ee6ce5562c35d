#version 460
#extension GL_GOOGLE_include_directive : require
// Step (b) of a round (core/volume/tet_parallel.h), over the candidates, in six dispatches
// (push.step): first the claims of every candidate's read set are set to 0 (no other claim is
// read, so the array is never zeroed whole); then every tet of a read set takes the largest
// key's high word (a 32-bit atomic maximum), then the largest tie word among the keys with that
// high word: together the largest 64-bit key, order-independent, in 32-bit texel atomics (no
// 128 MiB storage-buffer binding to outgrow, no 64-bit atomics to enable). A candidate is
// accepted when both words are its own at every tet of its read set: its key word gets
// kTetAccepted, its owner's bit goes into the 2–3 or 3–2 mask (for the slot allocation's prefix
// sums). The accepted ones then mark their read sets taken; each other one is listed for
// evaluation in the next round if its read set holds a taken tet, else carried over as it is.
// kTetStepClaimHigh also clears the evaluation bits of this round's evaluation list (read by
// tet_candidates.comp for the carried candidates).
#include "tet_plan.glsl"

void main() {
    const uint i = invocationIndex();
    if (push.step == kTetStepClaimHigh && i < control.eval_count)
        imageAtomicAnd(tet_state, int(imageLoad(eval_list, int(i)).x), ~kTetStateEval);
    if (i >= control.candidate_count) return;
    const uvec2 entry = imageLoad(candidate_list, int(i)).xy;
    const uint owner = entry.x & (kTetMaxSlots - 1u), site = entry.x >> kTetSiteShift;
    const bool accepted = (entry.y & kTetAccepted) != 0u;
    const uint high = entry.y & ~kTetAccepted, tie = tetTieWord(owner);
    if ((push.step == kTetStepTake && !accepted) || (push.step == kTetStepJudge && accepted)) return;
    uint read[12];
    uint kind;
    const uint count = readSetOfSite(owner, site, read, kind);
    if (push.step == kTetStepClaimHigh) {
        for (uint k = 0u; k < count; ++k) imageAtomicMax(claim_high, int(read[k]), high);
    } else if (push.step == kTetStepClaimLow) {
        for (uint k = 0u; k < count; ++k)
            if (imageLoad(claim_high, int(read[k])).x == high) imageAtomicMax(claim_low, int(read[k]), tie);
    } else if (push.step == kTetStepCheck) {
        bool all = true;
        for (uint k = 0u; k < count; ++k)
            all = all && imageLoad(claim_high, int(read[k])).x == high && imageLoad(claim_low, int(read[k])).x == tie;
        if (!all) return;
        imageStore(candidate_list, int(i), uvec4(entry.x, entry.y | kTetAccepted, 0u, 0u));
        if (kind == kKindTwoThree || kind == kKindThreeTwo)
            imageAtomicOr(masks, int(2u * (owner / 32u) + (kind == kKindTwoThree ? 0u : 1u)), 1u << (owner % 32u));
        atomicAdd(control.round_flips[kind], 1u);
    } else if (push.step == kTetStepTake) {
        for (uint k = 0u; k < count; ++k) imageStore(claim_high, int(read[k]), uvec4(kTetTaken));
    } else if (push.step == kTetStepJudge) {
        bool touched = false;
        for (uint k = 0u; k < count; ++k) touched = touched || imageLoad(claim_high, int(read[k])).x == kTetTaken;
        if (touched) listEval(owner);
        else imageStore(carried_list, int(atomicAdd(control.carry_count, 1u)), uvec4(entry, 0u, 0u));
    } else {
        for (uint k = 0u; k < count; ++k) {
            imageStore(claim_high, int(read[k]), uvec4(0u));
            imageStore(claim_low, int(read[k]), uvec4(0u));
        }
    }
}
