#version 460
#extension GL_GOOGLE_include_directive : require
// The edges a pass works on, listed (kSimplifyBindingListed, in no order; their count in the
// tallies), so that its invocations all have work: the passes after it look at a few percent
// of the edges, scattered (chelsea.png to 10 %, on average over the rounds: 12 % for the
// candidates, 1.6 % for the selection), and a device runs invocations in lockstep groups,
// which take as long as their busiest member. push.step picks which edges (kGather…); the host
// zeroes the count first.
#include "collapse_rule.glsl"

layout(binding = kSimplifyBindingCandidates, rgba32ui) uniform readonly uimageBuffer candidates;
layout(binding = kSimplifyBindingTallies, r32ui) uniform uimageBuffer tallies;

void main() {
    const uint e = invocationEdge();
    if (e == kNone) return;
    const uint cost_word = imageLoad(candidates, int(e)).x;
    bool listing;
    if (push.step == kGatherChanged) {
        const uvec4 ev = verticesOf(e);
        listing = ev.x == kNone ? cost_word != kNone
                                : imageLoad(changed, int(ev.x)).x != 0u || imageLoad(changed, int(ev.y)).x != 0u;
    } else {
        listing = cost_word <= push.cost_word_limit;
    }
    if (listing) imageStore(listed, int(imageAtomicAdd(tallies, int(kTallyListed), 1u)), uvec4(e));
}
