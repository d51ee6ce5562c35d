#include "tet_parallel.h"

#include <algorithm>
#include <cassert>
#include <vector>

namespace ddt {

namespace {

// bestFlipAt's edges, in its order.
constexpr uint8_t kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

// Rings that a flip may change: interior of degree 3 (3–2) or 4 (4–4), boundary of degree 2 (2–2).
bool flippableRing(const EdgeRing& ring) {
    return ring.interior ? ring.degree == 3 || ring.degree == 4 : ring.degree == 2;
}

uint32_t ringOwner(const EdgeRing& ring) {
    uint32_t owner = ring.tets[0];
    for (uint32_t k = 1; k < ring.degree; ++k) owner = std::min(owner, ring.tets[k]);
    return owner;
}

bool ringIsFlat(const TetCosts& costs, const EdgeRing& ring) {
    for (uint32_t k = 0; k < ring.degree; ++k)
        if (!costs.flat(ring.tets[k])) return false;
    return true;
}

// Per slot, the round in which it was last listed (0: never), so that a list holds each slot once.
class ListStamps {
public:
    bool list(uint32_t slot, uint32_t round) {
        if (slot >= stamps_.size()) stamps_.resize(size_t(slot) + 1, 0);
        if (stamps_[slot] == round) return false;
        stamps_[slot] = round;
        return true;
    }

private:
    std::vector<uint32_t> stamps_;
};

struct Candidate {
    uint32_t owner;
    uint64_t key;
    FlipPlan plan;
};

// Step (b): the candidates whose key is the claim of every tet of their read set.
std::vector<uint8_t> selectCandidates(const std::vector<Candidate>& candidates, std::vector<uint64_t>& claims) {
    std::array<uint32_t, 12> read;
    for (const Candidate& c : candidates) {
        const uint32_t count = c.plan.readSet(read);
        for (uint32_t k = 0; k < count; ++k) {
            if (read[k] >= claims.size()) claims.resize(size_t(read[k]) + 1, 0);
            claims[read[k]] = std::max(claims[read[k]], c.key);
        }
    }
    std::vector<uint8_t> accepted(candidates.size(), 0);
    for (size_t i = 0; i < candidates.size(); ++i) {
        const uint32_t count = candidates[i].plan.readSet(read);
        bool all = true;
        for (uint32_t k = 0; k < count; ++k) all = all && claims[read[k]] == candidates[i].key;
        accepted[i] = all;
    }
    for (const Candidate& c : candidates) {  // claims back to 0 for the next round
        const uint32_t count = c.plan.readSet(read);
        for (uint32_t k = 0; k < count; ++k) claims[read[k]] = 0;
    }
    return accepted;
}

// Step (c): the accepted plans, in owner order, with the slot rule of tet_parallel.h. The new
// tets' slots go to `new_slots`, every slot written or freed to `changed`.
void applyAccepted(TetMesh& mesh, const std::vector<const FlipPlan*>& accepted, std::vector<uint32_t>& new_slots,
                   std::vector<uint32_t>& changed) {
    const uint32_t free_count = uint32_t(mesh.free_slots.size()), slot_count = mesh.slotCount();
    uint32_t two_threes = 0;
    for (const FlipPlan* plan : accepted) two_threes += plan->kind == FlipKind::two_three;
    std::vector<uint32_t> taken(two_threes);
    for (uint32_t k = 0; k < two_threes; ++k)
        taken[k] = k < free_count ? mesh.free_slots[free_count - 1 - k] : slot_count + (k - free_count);
    mesh.free_slots.resize(free_count - std::min(two_threes, free_count));
    if (two_threes > free_count) {  // records for the appended slots, filled by their flips
        mesh.vertices.resize(size_t(slot_count) + two_threes - free_count, {kNoTet, kNoTet, kNoTet, kNoTet});
        mesh.neighbours.resize(mesh.vertices.size(), {kNoTet, kNoTet, kNoTet, kNoTet});
    }
    std::vector<uint32_t> freed;
    uint32_t k = 0;
    for (const FlipPlan* plan : accepted) {
        // applyFlip takes a 2–3's third slot from the top of free_slots and pushes a 3–2's
        // freed slot there: hand it the slot the rule chose, and hold the freed one back.
        if (plan->kind == FlipKind::two_three) mesh.free_slots.push_back(taken[k++]);
        const AppliedFlip applied = applyFlip(mesh, *plan);
        if (applied.freed != kNoTet) {
            assert(mesh.free_slots.back() == applied.freed);
            mesh.free_slots.pop_back();
            freed.push_back(applied.freed);
        }
        new_slots.insert(new_slots.end(), applied.slots.begin(), applied.slots.begin() + applied.count);
        changed.insert(changed.end(), applied.changed.begin(), applied.changed.begin() + applied.changed_count);
    }
    mesh.free_slots.insert(mesh.free_slots.end(), freed.begin(), freed.end());
}

}  // namespace

uint32_t ownerOf(const FlipPlan& plan) {
    uint32_t owner = plan.region[0];
    for (uint32_t k = 1; k < plan.region_count; ++k) owner = std::min(owner, plan.region[k]);
    return owner;
}

std::optional<FlipPlan> bestOwnedFlipAt(const TetMesh& mesh, const TetCosts& costs, uint32_t t) {
    assert(mesh.inUse(t));
    std::optional<FlipPlan> best;
    auto consider = [&](std::optional<FlipPlan>&& plan) {
        if (plan && plan->worthApplying() && (!best || plan->gain > best->gain)) best = std::move(plan);
    };
    for (uint32_t f = 0; f < 4; ++f) {
        const uint32_t n = mesh.neighbours[t][f];
        if (n == kNoTet || n < t || (costs.flat(t) && costs.flat(n))) continue;
        consider(planTwoThree(mesh, costs, t, f));
    }
    for (const auto& e : kEdges) {
        const std::optional<EdgeRing> ring = edgeRingOf(mesh, t, e[0], e[1], 4);
        if (!ring || !flippableRing(*ring) || ringOwner(*ring) != t || ringIsFlat(costs, *ring)) continue;
        consider(planEdgeFlip(mesh, costs, t, e[0], e[1]));
    }
    assert(!best || ownerOf(*best) == t);
    return best;
}

void forEachSiteOwner(const TetMesh& mesh, const TetCosts& costs, uint32_t t, const std::function<void(uint32_t)>& list) {
    assert(mesh.inUse(t));
    for (uint32_t f = 0; f < 4; ++f) {
        const uint32_t n = mesh.neighbours[t][f];
        if (n != kNoTet && !(costs.flat(t) && costs.flat(n))) list(std::min(t, n));
    }
    for (const auto& e : kEdges) {
        const std::optional<EdgeRing> ring = edgeRingOf(mesh, t, e[0], e[1], 4);
        if (ring && flippableRing(*ring) && !ringIsFlat(costs, *ring)) list(ringOwner(*ring));
    }
}

TetParallelStats optimizeTetMeshParallel(TetMesh& mesh, const TetCostField& field, const TetParallelOptions& options) {
    TetParallelStats stats;
    TetCosts costs(mesh, field, options.weight);
    stats.cost_before = costs.total();

    std::vector<uint64_t> claims(mesh.slotCount(), 0);
    ListStamps active_stamps, evaluate_stamps;
    std::vector<Candidate> candidates;
    std::vector<const FlipPlan*> accepted;
    std::vector<uint32_t> evaluate, new_slots, changed, active, losers;
    std::vector<Candidate> carried, carry_next;  // unaccepted candidates whose read sets no flip touched
    std::vector<uint32_t> taken;                 // per slot: the round whose flips' read sets hold it
    // The first round's active tets: those that are not flat, every site not all flat has one.
    for (uint32_t t = 0; t < mesh.slotCount(); ++t)
        if (mesh.inUse(t) && !costs.flat(t)) active.push_back(t);

    for (;;) {
        if (stats.rounds == options.max_rounds) {
            stats.capped = true;
            break;
        }
        // (d) of the last round: the tets to evaluate, ascending.
        const uint32_t stamp = stats.rounds + 1;
        evaluate.clear();
        auto list = [&](uint32_t owner) {
            if (evaluate_stamps.list(owner, stamp)) evaluate.push_back(owner);
        };
        if (options.evaluate_all) {
            for (uint32_t t = 0; t < mesh.slotCount(); ++t)
                if (mesh.inUse(t)) list(t);
        } else {
            for (uint32_t t : losers) list(t);
            for (uint32_t t : active) forEachSiteOwner(mesh, costs, t, list);
        }
        std::sort(evaluate.begin(), evaluate.end());

        // (a) candidates, in owner order.
        candidates.clear();
        for (uint32_t t : evaluate) {
            if (!mesh.inUse(t)) continue;  // freed by the last round
            ++stats.evaluated;
            if (std::optional<FlipPlan> plan = bestOwnedFlipAt(mesh, costs, t))
                candidates.push_back({t, tetFlipKey(plan->gain, t), *plan});
        }
        // The candidates carried over from the last round, unless their owners are evaluated anew.
        if (!carried.empty()) {
            for (Candidate& c : carried)
                if (evaluate_stamps.list(c.owner, stamp)) candidates.push_back(std::move(c));
            std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.owner < b.owner; });
        }
        stats.candidates += candidates.size();
        // (b) selection.
        const std::vector<uint8_t> chosen = selectCandidates(candidates, claims);
        accepted.clear();
        losers.clear();
        std::array<uint32_t, 12> read;
        if (taken.size() < mesh.slotCount()) taken.resize(mesh.slotCount(), 0);
        for (size_t i = 0; i < candidates.size(); ++i) {
            if (!chosen[i]) continue;
            accepted.push_back(&candidates[i].plan);
            ++stats.flips[uint32_t(candidates[i].plan.kind)];
            const uint32_t count = candidates[i].plan.readSet(read);
            for (uint32_t k = 0; k < count; ++k) taken[read[k]] = stamp;
        }
        // The others: evaluated anew next round where a flip touched their read sets, else carried
        // over as they are (their plans and gains read nothing that changed).
        carry_next.clear();
        for (size_t i = 0; i < candidates.size(); ++i) {
            if (chosen[i]) continue;
            const uint32_t count = candidates[i].plan.readSet(read);
            bool touched = false;
            for (uint32_t k = 0; k < count; ++k) touched = touched || taken[read[k]] == stamp;
            if (touched) losers.push_back(candidates[i].owner);
            else carry_next.push_back(candidates[i]);
        }
        // (c) flips and the cost cache.
        new_slots.clear();
        changed.clear();
        applyAccepted(mesh, accepted, new_slots, changed);
        costs.update(mesh, changed.data(), uint32_t(changed.size()));
        ++stats.rounds;
        if (options.after_round) options.after_round(stats.rounds, mesh, costs.total());
        if (accepted.empty()) break;

        carried.swap(carry_next);
        // (d) the next round's active tets: the new ones and, for face_scf, their neighbours.
        active.clear();
        for (uint32_t slot : new_slots) {
            if (active_stamps.list(slot, stamp)) active.push_back(slot);
            if (options.weight != TetWeight::face_scf) continue;
            for (uint32_t n : mesh.neighbours[slot])
                if (n != kNoTet && active_stamps.list(n, stamp)) active.push_back(n);
        }
    }
    stats.cost_after = costs.total();
    return stats;
}

}  // namespace ddt
