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

void setArgs(uint slot, uint groups) { args[slot] = uvec4(groups, 1, 1, 0); }

void planCandidates() {
    uint groups = 0;
    if (control.phase == kPhaseCandidates) {
        // Fold the finished iteration's flips into the 64-bit total.
        const uint low = control.total_flips_low + control.flips_in_iteration;
        if (low < control.total_flips_low) control.total_flips_high += 1;
        control.total_flips_low = low;
        control.flips_in_iteration = 0;
        if (control.iteration >= push.max_iterations) {
            control.phase = kPhaseDone;
            control.capped = 1;
        } else {
            const bool from_list = push.active_set != 0 && control.iteration > 0;
            groups = groupsFor(from_list ? control.active_count[control.iteration & 1] : push.edge_count);
            control.candidate_count = 0;
            control.round = 0;
            control.phase = kPhaseRounds;
        }
    }
    setArgs(kArgsCandidates, groups);
}

void planSelect() {
    uint groups = 0;
    if (control.phase == kPhaseRounds) {
        if (control.round == 0 && control.candidate_count == 0) {
            control.phase = kPhaseDone;  // locally optimal: nothing to flip
        } else if (control.round == 0 || (kSingleRound == 0 && control.undecided_count[control.round & 1] > 0 &&
                                    control.round < push.max_rounds)) {
            const uint next = (control.round + 1) & 1;
            groups = groupsFor(control.round == 0 ? control.candidate_count : control.round_count[control.round & 1]);
            control.round_count[next] = 0;
            control.undecided_count[next] = 0;
            control.round += 1;
            control.total_rounds += 1;
            control.max_rounds_in_iteration = max(control.max_rounds_in_iteration, control.round);
        }
    }
    setArgs(kArgsSelect, groups);
}

void planFlip() {
    uint groups = 0;
    if (control.phase == kPhaseRounds && control.round > 0) {
        const bool rounds_left = kSingleRound == 0 && control.undecided_count[control.round & 1] > 0;
        if (rounds_left && control.round >= push.max_rounds) control.capped = 1;  // the rest waits for the next iteration
        if (!rounds_left || control.round >= push.max_rounds) {
            groups = groupsFor(control.candidate_count);
            control.iteration += 1;
            control.active_count[control.iteration & 1] = 0;
            control.phase = kPhaseCandidates;
        }
    }
    setArgs(kArgsFlip, groups);
}

void main() {
    if (gl_GlobalInvocationID.x != 0) return;
    if (push.step == kArgsCandidates) planCandidates();
    else if (push.step == kArgsSelect) planSelect();
    else planFlip();
}
