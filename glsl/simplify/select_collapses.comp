#version 460
#extension GL_GOOGLE_include_directive : require
// Step 2 of a simplification round (core/simplify/parallel_simplify.h's selectWinners), over
// the keys whose cost word is at most a limit (listed by gather_edges.comp; the host picks the
// limit from the tally of all cost words, kSelectTallyCosts, over every edge). A collapse's
// region is its edge's two vertices and all their neighbours. Each pass: each vertex takes the
// least key among the undecided regions holding it; a collapse wins where its key is that of
// every vertex of its region, and marks its region taken; the undecided ones whose regions
// touch a taken vertex are out. push.step picks the step (kSelect…). The host zeroes the
// tallies, the taken marks and the edge states before the first pass, and fills the least
// arrays with all ones before each.
#include "collapse_rule.glsl"

layout(binding = kSimplifyBindingCandidates, rgba32ui) uniform readonly uimageBuffer candidates;
layout(binding = kSimplifyBindingLeastCost, r32ui) uniform coherent uimageBuffer least_cost;
layout(binding = kSimplifyBindingLeastTie, r32ui) uniform coherent uimageBuffer least_tie;
layout(binding = kSimplifyBindingWinners, rgba32ui) uniform writeonly uimageBuffer winners;
layout(binding = kSimplifyBindingTargets, rg32i) uniform readonly iimageBuffer targets;
layout(binding = kSimplifyBindingTallies, r32ui) uniform uimageBuffer tallies;
layout(binding = kSimplifyBindingTaken, r32ui) uniform uimageBuffer taken;
layout(binding = kSimplifyBindingEdgeState, r32ui) uniform uimageBuffer edge_state;

// One vertex of the region of an edge with key (cost_word, tie). `all` says whether every
// vertex so far holds that key (kSelectWinners), or none is taken (kSelectOut).
void visit(uint v, uint cost_word, uint tie, inout bool all) {
    if (push.step == kSelectLeastCost) imageAtomicMin(least_cost, int(v), cost_word);
    else if (push.step == kSelectLeastTie) {
        if (imageLoad(least_cost, int(v)).x == cost_word) imageAtomicMin(least_tie, int(v), tie);
    } else if (push.step == kSelectWinners) {
        all = all && imageLoad(least_cost, int(v)).x == cost_word && imageLoad(least_tie, int(v)).x == tie;
    } else {
        all = all && imageLoad(taken, int(v)).x == 0u;
    }
}

// Marks the vertices of edge e's region taken.
void takeRegion(uvec4 ev) {
    for (uint end = 0u; end < 2u; ++end) {
        const uint centre = end == 0u ? ev.x : ev.y;
        imageStore(taken, int(centre), uvec4(1u));
        for (Walk w = beginWalk(centre); w.f != kNone; advance(w))
            imageStore(taken, int(otherEnd(verticesOf(w.f), centre)), uvec4(1u));
    }
}

void main() {
    const uint e = invocationEdge();
    if (e == kNone) return;
    const uvec4 candidate = imageLoad(candidates, int(e));
    const uint cost_word = candidate.x, tie = candidate.y;
    if (cost_word == kNone) return;
    if (push.step == kSelectTallyCosts) {
        imageAtomicAdd(tallies, int(costBin(cost_word)), 1u);
        return;
    }
    if (imageLoad(edge_state, int(e)).x != kEdgeUndecided) return;
    bool all = true;
    const uvec4 ev = verticesOf(e);
    for (uint end = 0u; end < 2u; ++end) {
        const uint centre = end == 0u ? ev.x : ev.y;
        visit(centre, cost_word, tie, all);
        for (Walk w = beginWalk(centre); w.f != kNone; advance(w))
            visit(otherEnd(verticesOf(w.f), centre), cost_word, tie, all);
    }
    if (push.step == kSelectWinners && all) {
        imageStore(edge_state, int(e), uvec4(kEdgeWon));
        const uint slot = imageAtomicAdd(tallies, int(kTallyWinners), 1u);
        imageStore(winners, int(2u * slot), candidate);
        imageStore(winners, int(2u * slot + 1u), uvec4(imageLoad(targets, int(e))));
        takeRegion(ev);
    } else if (push.step == kSelectOut && !all) {
        imageStore(edge_state, int(e), uvec4(kEdgeOut));
    }
}
