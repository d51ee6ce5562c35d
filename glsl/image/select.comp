#version 460
#extension GL_GOOGLE_include_directive : require
// Step 2 (paper Sec. 3.2), one accept/reject round over the undecided candidates:
// a candidate with an accepted edge in its ROI is rejected; one that beats every undecided
// candidate in its ROI is accepted; any other stays undecided for the next round.
//
// The region is the 2-region (ExpROI: the 3-region) for every cost (kCost). Sederberg's and
// face-SCF's gains have exactly this ROI. Variance's gain reads e's record only, so its ROI is
// the 1-region; but glsl/image/flip.comp patches an accepted edge's four neighbours without locks,
// which needs the closed 1-regions of accepted edges disjoint: no accepted edge in another's
// 2-region. Two edges on opposite sides of one neighbour would otherwise both rewrite its
// record. So variance keeps the 2-region too, for the flips' sake.
// Rounds are synchronous: round r reads status[r & 1] and writes status[(r + 1) & 1] (bindings status0/status1), so
// the outcome does not depend on thread timing. An edge decided in round r is listed once
// more, as a copy entry, to carry its decision into the other status array.
//
// Variants (paper Sec. 5, plus local-max) are parameters of this one kernel:
// - kKeyByGain: MaxGain — the higher gain wins, equal gains by the lower id (the exact
//   double gains are compared, so the order is total and deterministic); else the lower id.
// - ROI degree: the 3-region (ExpROI) in iterations below exproi_iterations, else the 2-region.
// - kSingleRound: local-max — one round only; candidates left undecided are not flipped in
//   this iteration and are tested again in the next.
#include "common.glsl"

layout(constant_id = 0) const uint kKeyByGain = 0;
layout(constant_id = 1) const uint kSingleRound = 0;

// Whether candidate e wins against candidate f.
bool beats(uint e, double gain_e, uint f) {
    if (kKeyByGain != 0) {
        const double gain_f = gainOf(f);
        if (gain_e != gain_f) return gain_e > gain_f;
    }
    return e < f;
}

// Visits the ROI of e level by level (neighbours, their neighbours, and for degree 3 theirs);
// an edge may be visited twice, which changes neither test. A neighbour's neighbours include e
// and the neighbour of e that shares its triangle: those, already visited, are skipped, which
// saves 4 of the 2-region's 20 visits (each a status and a gain load).
uint decide(uint e, uint parity_in, uint degree) {
    const double gain_e = kKeyByGain != 0 ? gainOf(e) : 0.0lf;
    bool best = true;
    const uvec4 level1 = neighboursOf(e);
    for (int i = 0; i < 4; ++i) {
        const uint f1 = level1[i];
        if (f1 == kNone) continue;
        uint status = statusOf(parity_in, f1);
        if (status == kStatusAccepted) return kStatusRejected;
        if (status == kStatusUndecided && !beats(e, gain_e, f1)) best = false;
        const uvec4 level2 = neighboursOf(f1);
        for (int j = 0; j < 4; ++j) {
            const uint f2 = level2[j];
            if (f2 == kNone || f2 == e || any(equal(level1, uvec4(f2)))) continue;
            status = statusOf(parity_in, f2);
            if (status == kStatusAccepted) return kStatusRejected;
            if (status == kStatusUndecided && !beats(e, gain_e, f2)) best = false;
            if (degree < 3) continue;
            const uvec4 level3 = neighboursOf(f2);
            for (int k = 0; k < 4; ++k) {
                const uint f3 = level3[k];
                if (f3 == kNone || f3 == e) continue;
                status = statusOf(parity_in, f3);
                if (status == kStatusAccepted) return kStatusRejected;
                if (status == kStatusUndecided && !beats(e, gain_e, f3)) best = false;
            }
        }
    }
    return best ? kStatusAccepted : kStatusUndecided;
}

uint roundListEntry(uint parity, uint i) {
    return parity == 0 ? imageLoad(round_list0, int(i)).x : imageLoad(round_list1, int(i)).x;
}

void appendToRoundList(uint parity, uint entry) {
    const uint slot = atomicAdd(control.round_count[parity], 1);
    if (parity == 0) imageStore(round_list0, int(slot), uvec4(entry));
    else imageStore(round_list1, int(slot), uvec4(entry));
}

void main() {
    const uint round = control.round - 1;  // the plan step counted this round already
    const uint parity_in = round & 1, parity_out = (round + 1) & 1;
    const uint count = round == 0 ? control.candidate_count : control.round_count[parity_in];
    const uint degree = control.iteration < push.exproi_iterations ? 3 : 2;

    for (uint i = gl_GlobalInvocationID.x; i < count; i += invocationStride()) {
        const uint entry = round == 0 ? imageLoad(candidate_list, int(i)).x : roundListEntry(parity_in, i);
        const uint e = entry & ~kCopyEntry;
        if ((entry & kCopyEntry) != 0) {
            setStatus(parity_out, e, statusOf(parity_in, e));
            continue;
        }
        const uint decision = decide(e, parity_in, degree);
        setStatus(parity_out, e, decision);
        // An edge is accepted once (later rounds only copy the decision): listed once for flip.comp.
        if (decision == kStatusAccepted) imageStore(accepted_list, int(atomicAdd(control.flips_in_iteration, 1)), uvec4(e));
        if (kSingleRound != 0) continue;
        appendToRoundList(parity_out, decision == kStatusUndecided ? e : (e | kCopyEntry));
        if (decision == kStatusUndecided) atomicAdd(control.undecided_count[parity_out], 1);
    }
}
