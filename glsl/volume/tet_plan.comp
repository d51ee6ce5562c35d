#version 460
#extension GL_GOOGLE_include_directive : require
// The rounds' state machine, one invocation before each step's dispatch: if the step is the
// one due (control.next_step) it does the step's bookkeeping, writes the step's indirect
// dispatch size and names the next step; otherwise the step's dispatch is empty. The host
// records several rounds of steps in one command buffer and reads `phase` after each submit:
// no host round trip per round, and once done the remaining dispatches are empty. When the
// round's flips need more slots than the arrays hold, the machine stops before kTetStepApply
// (kTetPhaseGrow); the host grows the arrays and resubmits, and the round goes on there.
#include "tet_common.glsl"

// Groups of kTetGroupSize for `count` items, in a second dimension beyond kTetMaxGroups.
void setArgs(uint count) {
    const uint groups = (count + kTetGroupSize - 1u) / kTetGroupSize;
    const uint rows = (groups + kTetMaxGroups - 1u) / kTetMaxGroups;
    args[push.step] = groups <= kTetMaxGroups ? uvec4(groups, 1u, 1u, 0u) : uvec4((groups + rows - 1u) / rows, rows, 1u, 0u);
}

void main() {
    if (gl_GlobalInvocationID.x != 0u) return;
    if (control.phase != kTetPhaseRunning || control.next_step != push.step) {
        args[push.step] = uvec4(0u, 1u, 1u, 0u);
        return;
    }
    uint next = push.step + 1u;
    switch (push.step) {
        case kTetStepMark:
            if (control.rounds >= push.max_rounds) {
                control.capped = 1u;
                control.phase = kTetPhaseDone;
                args[push.step] = uvec4(0u, 1u, 1u, 0u);
                return;
            }
            setArgs(control.active_count);
            break;
        case kTetStepCandidates:
            control.active_count = 0u;  // read by the mark step; the flips list the next ones
            control.candidate_count = 0u;
            control.skipped = 0u;
            setArgs(control.eval_count + control.carry_count);
            break;
        case kTetStepClaimHigh:
            control.evaluated += control.eval_count - control.skipped;
            control.candidates += control.candidate_count;
            control.carry_count = 0u;  // read by the candidates; the judge step lists the next ones
            if (control.candidate_count == 0u) {  // a local optimum: the round accepts nothing
                control.rounds += 1u;
                control.phase = kTetPhaseDone;
                args[push.step] = uvec4(0u, 1u, 1u, 0u);
                return;
            }
            for (uint k = 0u; k < 4u; ++k) control.round_flips[k] = 0u;
            setArgs(max(control.candidate_count, control.eval_count));  // and the evaluation bits
            break;
        case kTetStepClaimLow:
            control.eval_count = 0u;  // its bits cleared; the judge step lists the next ones
            setArgs(control.candidate_count);
            break;
        case kTetStepClear:
        case kTetStepCheck:
        case kTetStepTake:
        case kTetStepJudge:
            setArgs(control.candidate_count);
            break;
        case kTetStepScan:
        case kTetStepUnmask:
            args[push.step] = uvec4(push.blocks, 1u, 1u, 0u);
            if (push.step == kTetStepUnmask) {
                for (uint k = 0u; k < 4u; ++k) control.flips[k] += uint64_t(control.round_flips[k]);
                control.rounds += 1u;
                next = kTetStepMark;
            }
            break;
        case kTetStepApply: {
            // The blocks' prefix sums, and the round's totals.
            uvec2 running = uvec2(0u);
            for (uint b = 0u; b < push.blocks; ++b) {
                const uvec2 total = imageLoad(blocks, int(b)).xy;
                imageStore(blocks, int(b), uvec4(total, running));
                running += total;
            }
            const uint free_count = control.free_count, two_threes = running.x;
            const uint appended = two_threes > free_count ? two_threes - free_count : 0u;
            if (control.slot_count + appended > push.capacity) {
                control.need = control.slot_count + appended;
                control.phase = kTetPhaseGrow;
                args[push.step] = uvec4(0u, 1u, 1u, 0u);
                return;
            }
            control.two_threes = two_threes;
            control.three_twos = running.y;
            control.base_free = free_count;
            control.base_slots = control.slot_count;
            setArgs(control.candidate_count);
            break;
        }
        case kTetStepRefresh: {
            const uint taken = min(control.two_threes, control.base_free);
            control.slot_count = control.base_slots + (control.two_threes - taken);
            control.free_count = control.base_free - taken + control.three_twos;
            control.new_count = control.active_count;
            setArgs(max(control.new_count, control.three_twos));
            break;
        }
        case kTetStepCosts:
            setArgs(control.active_count);
            break;
    }
    control.next_step = next;
}
