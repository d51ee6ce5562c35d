#version 460
#extension GL_GOOGLE_include_directive : require
// Step (c) of a round (core/volume/tet_parallel.h): each accepted candidate's flip, as core's
// applyFlip, with the slot rule: a 2–3 of rank k among the round's accepted 2–3 flips in owner
// order takes free_slots[F − 1 − k] while k < F, else slot base_slots + k − F; a 3–2 of rank j
// among the 3–2 flips puts its freed slot at freed[j] (tet_refresh.comp pushes them after the
// free slots left). Accepted read sets are disjoint and hold everything a flip reads or writes
// (but the free slot it takes, which is its alone), so the flips run in any order, together.
// The new tets are listed in the active list; a freed slot's cache entries are cleared as
// TetCosts::update clears them.
#include "tet_plan.glsl"

uint rankOf(uint owner, uint kind) {
    const uint word = owner / 32u;
    const uvec4 block = imageLoad(blocks, int(word / kTetScanWords));
    const uint below = imageLoad(masks, int(2u * word + kind)).x & ((1u << (owner % 32u)) - 1u);
    return (kind == 0u ? block.z : block.w) + imageLoad(word_prefix, int(word))[kind] + bitCount(below);
}

void main() {
    const uint i = invocationIndex();
    if (i >= control.candidate_count) return;
    const uvec2 entry = imageLoad(candidate_list, int(i)).xy;
    if ((entry.y & kTetAccepted) == 0u) return;
    const uint owner = entry.x & (kTetMaxSlots - 1u), site = entry.x >> kTetSiteShift;
    planOfSite(owner, site);
    uint slots[4];
    for (uint k = 0u; k < plan.new_count; ++k) slots[k] = k < plan.region_count ? plan.region[k] : kNoTet;
    if (plan.kind == kKindTwoThree) {
        const uint rank = rankOf(owner, 0u), free_count = control.base_free;
        if (rank < free_count) {
            slots[2] = imageLoad(free_slots, int(free_count - 1u - rank)).x;
        } else {
            // A slot beyond the ones in use: its state word was never zeroed (tet_device.cpp).
            slots[2] = control.base_slots + (rank - free_count);
            imageStore(tet_state, int(slots[2]), uvec4(0u));
        }
    }
    for (uint k = 0u; k < plan.new_count; ++k) imageStore(tet_vertices, int(slots[k]), plan.new_tets[k]);
    for (uint k = 0u; k < plan.new_count; ++k) {
        uvec4 links;
        for (uint f = 0u; f < 4u; ++f) {
            const uint link = plan.links[4u * k + f];
            if (link < 4u) {
                links[f] = slots[link];
            } else if (link == kBoxSideLink) {
                links[f] = kNoTet;
            } else {
                const uint h = link - 4u, outside = plan.hull_outside[h];
                links[f] = outside;
                if (outside != kNoTet) {
                    uvec4 back = neighboursOf(outside);
                    back[plan.hull_back[h]] = slots[k];
                    imageStore(tet_neighbours, int(outside), back);
                }
            }
        }
        imageStore(tet_neighbours, int(slots[k]), links);
    }
    for (uint k = plan.new_count; k < plan.region_count; ++k) {
        const uint slot = plan.region[k];
        imageStore(tet_vertices, int(slot), uvec4(kNoTet));
        imageStore(tet_neighbours, int(slot), uvec4(kNoTet));
        if (push.face_scf != 0u) {
            imageStore(tet_cost, int(slot), uvec4(0u));
            for (uint a = 0u; a < 3u; ++a) imageStore(tet_gradient, int(3u * slot + a), uvec4(0u));
        }
        imageAtomicOr(tet_state, int(slot), kTetStateFlat);
        imageStore(freed_slots, int(rankOf(owner, 1u)), uvec4(slot));
    }
    for (uint k = 0u; k < plan.new_count; ++k) listActive(slots[k]);
}
