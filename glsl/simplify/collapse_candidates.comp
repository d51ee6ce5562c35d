#version 460
#extension GL_GOOGLE_include_directive : require
// Step 1 of a simplification round (core/simplify/parallel_simplify.h): every edge's best
// legal collapse within the error limit, the merged vertex placed as core's placeCollapses
// places it, keyed by its cost's high 32 bits and tieOrder(e); b into a, tried first, stays on
// equal keys. No candidate: both key words all ones. Only the listed edges, whose candidate may
// have changed (gather_edges.comp; core's markRingChanged says why that is enough).
#include "collapse_rule.glsl"

layout(binding = kSimplifyBindingCandidates, rgba32ui) uniform writeonly uimageBuffer candidates;
layout(binding = kSimplifyBindingTargets, rg32i) uniform writeonly iimageBuffer targets;

void main() {
    const uint e = invocationEdge();
    if (e == kNone) return;
    uvec4 best = uvec4(kNone, kNone, kCandidateBIntoA, 0u);  // as core: no candidate reads as b into a
    ivec2 best_target = ivec2(0);
    const uvec4 ev = verticesOf(e);
    if (ev.x != kNone && eitherWayLegal(e)) {
        const QuadricSum sum = quadricSum(ev.x, ev.y);
        const double error_limit = packDouble2x32(uvec2(push.error_limit_low, push.error_limit_high));
        Placed both[2];
        placeCollapses(sum, e, both);
        for (uint direction = 1u; direction <= 1u; --direction) {  // b into a, then a into b
            const Placed placed = both[direction];
            if (!placed.moves && !directionLegal(e, direction == 1u, false, ivec2(0))) continue;  // a move is legal
            if (exceedsErrorLimit(placed.cost, sum.area, error_limit)) continue;
            const uint cost_word = unpackDouble2x32(placed.cost).y;
            if (cost_word < best.x) {
                best = uvec4(cost_word, tieOrder(e), direction | (placed.moves ? kCandidateMoves : 0u), e);
                best_target = placed.moves ? placed.target : ivec2(0);
            }
        }
    }
    imageStore(candidates, int(e), best);
    imageStore(targets, int(e), ivec4(best_target, 0, 0));
}
