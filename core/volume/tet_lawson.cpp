#include "tet_lawson.h"

#include <algorithm>
#include <vector>

namespace ddt {

TetLawsonStats optimizeTetMeshSerial(TetMesh& mesh, const TetCostField& field, const TetLawsonOptions& options) {
    TetLawsonStats stats;
    TetCosts costs(mesh, field, options.weight);
    stats.cost_before = costs.total();

    std::vector<uint32_t> active, candidates;
    active.reserve(mesh.tetCount());
    for (uint32_t t = 0; t < mesh.slotCount(); ++t)
        if (mesh.inUse(t)) active.push_back(t);
    // Per slot: 1 while waiting in the active list, 2 while in the candidate list.
    std::vector<uint8_t> listed(mesh.slotCount(), 0);
    constexpr uint8_t kActive = 1, kCandidate = 2;
    for (uint32_t t : active) listed[t] = kActive;

    auto queue = [&](uint32_t t) {
        if (t == kNoTet || listed[t] != 0) return;
        listed[t] = kCandidate;
        candidates.push_back(t);
    };

    for (;;) {
        if (stats.iterations == options.max_iterations) {
            stats.capped = true;
            break;
        }
        uint64_t applied_now = 0;
        for (uint32_t t : active) {
            if (listed[t] == kActive) listed[t] = 0;
            if (!mesh.inUse(t)) continue;
            const std::optional<FlipPlan> plan = bestFlipAt(mesh, costs, t);
            if (!plan) continue;
            const AppliedFlip applied = applyFlip(mesh, costs, *plan);
            if (listed.size() < mesh.slotCount()) listed.resize(mesh.slotCount(), 0);
            ++stats.flips[uint32_t(plan->kind)];
            ++applied_now;
            for (uint32_t k = 0; k < applied.count; ++k) {
                const uint32_t slot = applied.slots[k];
                queue(slot);
                if (options.weight == TetWeight::face_scf)
                    for (uint32_t n : mesh.neighbours[slot]) queue(n);
            }
        }
        ++stats.iterations;
        if (options.after_iteration) options.after_iteration(stats.iterations, mesh, costs.total());
        if (applied_now == 0) break;
        // A freed slot may have been queued before it was freed; the loop skips it.
        std::sort(candidates.begin(), candidates.end());
        active.swap(candidates);
        candidates.clear();
        for (uint32_t t : active) listed[t] = kActive;
    }
    stats.cost_after = costs.total();
    return stats;
}

}  // namespace ddt
