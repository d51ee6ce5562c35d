#version 460
#extension GL_GOOGLE_include_directive : require
// Step 1 of a simplification round (core/simplify/parallel_simplify.h): every edge's best
// legal collapse within the error limit, keyed by its cost's high 32 bits and tieOrder(e); b into
// a, tried first, stays on equal keys. No candidate: both key words all ones. Only the listed
// edges, whose candidate may have changed (gather_edges.comp; core's markRingChanged says why
// that is enough).
#include "collapse_rule.glsl"

layout(binding = kSimplifyBindingCandidates, rgba32ui) uniform writeonly uimageBuffer candidates;

void main() {
    const uint e = invocationEdge();
    if (e == kNone) return;
    uvec4 best = uvec4(kNone, kNone, 1u, 0u);  // as core: no candidate reads as b into a
    const uvec4 ev = verticesOf(e);
    if (ev.x != kNone && eitherWayLegal(e)) {
        const bool legal[2] = {directionLegal(e, false), directionLegal(e, true)};
        if (legal[0] || legal[1]) {
            const QuadricSum sum = quadricSum(ev.x, ev.y);
            const double error_limit = packDouble2x32(uvec2(push.error_limit_low, push.error_limit_high));
            for (uint direction = 1u; direction <= 1u; --direction) {  // b into a, then a into b
                if (!legal[direction]) continue;
                const uint to = direction == 1u ? ev.x : ev.y;
                const double cost = collapseCost(sum, to);
                if (exceedsErrorLimit(cost, sum.area, error_limit)) continue;
                const uint cost_word = unpackDouble2x32(cost).y;
                if (cost_word < best.x) best = uvec4(cost_word, tieOrder(e), direction, e);
            }
        }
    }
    imageStore(candidates, int(e), best);
}
