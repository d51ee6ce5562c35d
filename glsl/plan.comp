#version 460
#extension GL_GOOGLE_include_directive : require
// The optimisation's state machine, run by one invocation before each working kernel: it
// writes that kernel's indirect dispatch size (zero when the kernel has nothing to do) and
// advances the phase. The host records many iterations' worth of
//   plan(candidates) candidates [plan(select) select]×K plan(flip) flip
// in one command buffer, submits it, and reads `phase` afterwards: no host round trip per
// iteration or round, and once converged the remaining dispatches are empty.
#include "common.glsl"

layout(constant_id = 1) const uint kSingleRound = 0;

void setArgs(uint slot, uint groups) {
    params.args.at[slot] = uvec3(groups, 1, 1);
    if (groups > 0) params.control.working_dispatches += 1;
}

void planCandidates(Control c) {
    uint groups = 0;
    if (c.phase == kPhaseCandidates) {
        // Fold the finished iteration's flips into the 64-bit total.
        const uint low = c.total_flips_low + c.flips_in_iteration;
        if (low < c.total_flips_low) c.total_flips_high += 1;
        c.total_flips_low = low;
        c.flips_in_iteration = 0;
        if (c.iteration >= params.max_iterations) {
            c.phase = kPhaseDone;
            c.capped = 1;
        } else {
            const bool from_list = params.active_set != 0 && c.iteration > 0;
            groups = groupsFor(from_list ? c.active_count[c.iteration & 1] : params.edge_count);
            c.candidate_count = 0;
            c.round = 0;
            c.phase = kPhaseRounds;
        }
    }
    setArgs(kArgsCandidates, groups);
}

void planSelect(Control c) {
    uint groups = 0;
    if (c.phase == kPhaseRounds) {
        if (c.round == 0 && c.candidate_count == 0) {
            c.phase = kPhaseDone;  // locally optimal: nothing to flip
        } else if (c.round == 0 || (kSingleRound == 0 && c.undecided_count[c.round & 1] > 0 &&
                                    c.round < params.max_rounds)) {
            const uint next = (c.round + 1) & 1;
            groups = groupsFor(c.round == 0 ? c.candidate_count : c.round_count[c.round & 1]);
            c.round_count[next] = 0;
            c.undecided_count[next] = 0;
            c.round += 1;
            c.total_rounds += 1;
            c.max_rounds_in_iteration = max(c.max_rounds_in_iteration, c.round);
        }
    }
    setArgs(kArgsSelect, groups);
}

void planFlip(Control c) {
    uint groups = 0;
    if (c.phase == kPhaseRounds && c.round > 0) {
        const bool rounds_left = kSingleRound == 0 && c.undecided_count[c.round & 1] > 0;
        if (rounds_left && c.round >= params.max_rounds) c.capped = 1;  // the rest waits for the next iteration
        if (!rounds_left || c.round >= params.max_rounds) {
            groups = groupsFor(c.candidate_count);
            c.iteration += 1;
            c.active_count[c.iteration & 1] = 0;
            c.phase = kPhaseCandidates;
        }
    }
    setArgs(kArgsFlip, groups);
}

void main() {
    loadParams();
    if (gl_GlobalInvocationID.x != 0) return;
    Control c = params.control;
    if (push.step == kArgsCandidates) planCandidates(c);
    else if (push.step == kArgsSelect) planSelect(c);
    else planFlip(c);
}
