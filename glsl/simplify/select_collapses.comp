#version 460
#extension GL_GOOGLE_include_directive : require
// Step 2 of a simplification round (core/simplify/parallel_simplify.h's selectWinners): a
// collapse's region is its edge's two vertices and all their neighbours; each vertex takes the
// least key among the regions holding it, and a collapse wins where its key is that of every
// vertex of its region. Only the keys whose cost word is at most a limit take part (listed by
// gather_edges.comp), which leaves every winner among them a winner (selectWinners says why);
// the host picks the limit from the tally of all cost words (kSelectTallyCosts, over every
// edge). push.step picks the pass (kSelect…); the host fills both least arrays with all ones
// and zeroes the tallies first.
#include "collapse_rule.glsl"

layout(binding = kSimplifyBindingCandidates, rgba32ui) uniform readonly uimageBuffer candidates;
layout(binding = kSimplifyBindingLeastCost, r32ui) uniform coherent uimageBuffer least_cost;
layout(binding = kSimplifyBindingLeastId, r32ui) uniform coherent uimageBuffer least_id;
layout(binding = kSimplifyBindingWinners, rgba32ui) uniform writeonly uimageBuffer winners;
layout(binding = kSimplifyBindingTallies, r32ui) uniform uimageBuffer tallies;

// One vertex of edge e's region, whose key is (cost_word, e); `least` says whether every
// vertex so far holds that key (kSelectWinners).
void visit(uint v, uint e, uint cost_word, inout bool least) {
    if (push.step == kSelectLeastCost) {
        imageAtomicMin(least_cost, int(v), cost_word);
    } else if (push.step == kSelectLeastId) {
        if (imageLoad(least_cost, int(v)).x == cost_word) imageAtomicMin(least_id, int(v), e);
    } else {
        least = least && imageLoad(least_cost, int(v)).x == cost_word && imageLoad(least_id, int(v)).x == e;
    }
}

void main() {
    const uint e = invocationEdge();
    if (e == kNone) return;
    const uvec4 candidate = imageLoad(candidates, int(e));
    const uint cost_word = candidate.x;
    if (cost_word == kNone) return;
    if (push.step == kSelectTallyCosts) {
        imageAtomicAdd(tallies, int(costBin(cost_word)), 1u);
        return;
    }
    bool least = true;
    const uvec4 ev = verticesOf(e);
    for (uint end = 0u; end < 2u; ++end) {
        const uint centre = end == 0u ? ev.x : ev.y;
        visit(centre, e, cost_word, least);
        for (Walk w = beginWalk(centre); w.f != kNone; advance(w))
            visit(otherEnd(verticesOf(w.f), centre), e, cost_word, least);
    }
    if (push.step == kSelectWinners && least)
        imageStore(winners, int(imageAtomicAdd(tallies, int(kTallyWinners), 1u)), candidate);
}
