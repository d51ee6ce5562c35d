// The parallel flip rule for tets (core/volume/tet_parallel.h) against its invariants and
// against the serial generalized Lawson (core/volume/tet_lawson.h).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "tet_test_support.h"
#include "tet_cost.h"
#include "tet_flips.h"
#include "tet_lawson.h"
#include "tet_mesh.h"
#include "tet_parallel.h"

using ddt::FlipKind;
using ddt::TetWeight;

using namespace ddt::test;

namespace {

// Runs the parallel rule from the Kuhn mesh and checks its invariants after every round and at
// the end: a valid mesh, the cached cost equal to a recomputation and never rising, and no tet
// owning a flip worth applying (a brute-force look at every tet's owned sites).
ddt::TetParallelStats optimizeChecked(ddt::TetMesh& mesh, const ddt::TetCostField& field, TetWeight weight) {
    INFO(ddt::tetWeightName(weight));
    const double initial_cost = ddt::meshCost(mesh, field, weight);
    double previous_cost = initial_cost;
    uint32_t rounds = 0;
    bool valid = true, exact = true, monotone = true, counted = true;
    ddt::TetParallelOptions options;
    options.weight = weight;
    options.after_round = [&](uint32_t round, const ddt::TetMesh& now, double cost) {
        counted = counted && round == rounds + 1;
        rounds = round;
        const std::string problem = ddt::checkTetMesh(now);
        if (!problem.empty()) {
            UNSCOPED_INFO("round " << round << ": " << problem);
            valid = false;
        }
        exact = exact && cost == ddt::meshCost(now, field, weight);
        // Every accepted flip lowers the exact cost; the compensated total rounds at ~1e-16.
        if (cost > previous_cost + 1e-13 * (1.0 + std::abs(previous_cost))) {
            UNSCOPED_INFO("round " << round << ": cost rose from " << previous_cost << " to " << cost);
            monotone = false;
        }
        previous_cost = cost;
    };
    const ddt::TetParallelStats stats = ddt::optimizeTetMeshParallel(mesh, field, options);
    CHECK(valid);
    CHECK(exact);
    CHECK(monotone);
    CHECK(counted);
    CHECK_FALSE(stats.capped);
    CHECK(stats.rounds == rounds);
    CHECK(stats.cost_before == initial_cost);
    CHECK(stats.cost_after == ddt::meshCost(mesh, field, weight));
    CHECK(stats.cost_after <= stats.cost_before);
    CHECK(stats.candidates >= stats.flipCount());
    const ddt::TetCosts costs(mesh, field, weight);
    uint32_t improvable = 0;
    for (uint32_t t = 0; t < mesh.slotCount(); ++t)
        if (mesh.inUse(t)) improvable += ddt::bestOwnedFlipAt(mesh, costs, t).has_value();
    CHECK(improvable == 0);
    return stats;
}

}  // namespace

TEST_CASE("tet parallel: every flip has one owner, who finds it as bestFlipAt's rule would", "[tet-parallel]") {
    // On a scrambled mesh: each tet's best owned flip is owned by it and is, among the flips
    // bestFlipAt sees from that tet, the best one it owns; and the owners listed for a tet's
    // sites are the smallest slots of those sites' regions.
    const ddt::TetCostField field = randomField({5, 4, 4}, 3, 4);
    ddt::TetMesh mesh = ddt::kuhnTetMesh(field.size);
    ddt::TetParallelOptions options;
    options.weight = TetWeight::variance;
    options.max_rounds = 2;
    ddt::optimizeTetMeshParallel(mesh, field, options);
    REQUIRE(ddt::checkTetMesh(mesh) == "");
    for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
        const ddt::TetCosts costs(mesh, field, weight);
        uint32_t proposals = 0;
        for (uint32_t t = 0; t < mesh.slotCount(); ++t) {
            if (!mesh.inUse(t)) continue;
            const std::optional<ddt::FlipPlan> plan = ddt::bestOwnedFlipAt(mesh, costs, t);
            if (!plan) continue;
            ++proposals;
            CHECK(ddt::ownerOf(*plan) == t);
            CHECK(plan->worthApplying());
            CHECK(plan->region[0] == t);
            // Listed as its own site's owner.
            bool listed = false;
            ddt::forEachSiteOwner(mesh, costs, t, [&](uint32_t owner) { listed = listed || owner == t; });
            CHECK(listed);
        }
        CHECK(proposals > 0);
    }
}

TEST_CASE("tet parallel: the key orders by gain, then by the owner's tie word", "[tet-parallel]") {
    CHECK(ddt::tetFlipKey(2.0, 7) > ddt::tetFlipKey(1.0, 7));
    CHECK(ddt::tetFlipKey(1e-300, 1) < ddt::tetFlipKey(1e-299, 0));
    // Gains within 2^-20 of each other tie; the tie word decides, and it differs per owner.
    const double gain = 0.75, close = gain * (1.0 + std::ldexp(1.0, -30));
    CHECK(ddt::tetFlipKey(gain, 5) >> 32 == ddt::tetFlipKey(close, 9) >> 32);
    CHECK(ddt::tetFlipKey(gain, 5) != ddt::tetFlipKey(close, 9));
    std::vector<uint32_t> words;
    for (uint32_t owner = 0; owner < 4096; ++owner) words.push_back(ddt::tetTieWord(owner));
    std::sort(words.begin(), words.end());
    CHECK(std::adjacent_find(words.begin(), words.end()) == words.end());
}

TEST_CASE("tet parallel: a sphere and a slanted plane: valid rounds, falling cost, a local optimum", "[tet-parallel]") {
    struct Case {
        const char* name;
        ddt::TetCostField field;
    };
    const Case cases[] = {{"sphere", sphereField(9, 3.0)}, {"slanted plane", slantedPlaneField(8, {0.8, 0.8, 2.0})}};
    for (const Case& c : cases)
        for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
            INFO(c.name << ", " << ddt::tetWeightName(weight));
            ddt::TetMesh mesh = ddt::kuhnTetMesh(c.field.size);
            const ddt::TetParallelStats stats = optimizeChecked(mesh, c.field, weight);
            CHECK(stats.flipCount() > 0);
            CHECK(stats.cost_after < stats.cost_before);
            CHECK(stats.rounds >= 2);  // the last round accepts nothing
        }
}

TEST_CASE("tet parallel: random values: 2-3 flips take free slots from the top, then append, and 3-2 flips free them", "[tet-parallel]") {
    // The mesh of one random field, compacted (no free slots), optimized for another: its first
    // rounds have 2–3 flips and no free slot, so slots are appended; 3–2 flips free slots that
    // later 2–3 flips take.
    for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
        INFO(ddt::tetWeightName(weight));
        const ddt::TetCostField first = randomField({7, 6, 5}, 1, 1000), second = randomField({7, 6, 5}, 2, 1000);
        ddt::TetParallelOptions options;
        options.weight = weight;
        ddt::TetMesh mesh = ddt::kuhnTetMesh(first.size);
        ddt::optimizeTetMeshParallel(mesh, first, options);
        mesh = compacted(mesh);
        REQUIRE(ddt::checkTetMesh(mesh) == "");
        const uint32_t initial_slots = mesh.slotCount();
        // The slot rule, round by round, read off the mesh before and after: the 2–3 flips took
        // the top `taken` free slots and appended the rest (only once the free slots ran out);
        // the slots the round freed were pushed after the free slots left.
        ddt::TetMesh before = mesh;
        uint32_t appended = 0, taken_total = 0;
        bool rule = true;
        options.after_round = [&](uint32_t round, const ddt::TetMesh& after, double) {
            const uint32_t free_before = uint32_t(before.free_slots.size());
            uint32_t taken = 0;
            std::vector<uint32_t> freed;
            for (uint32_t t : before.free_slots) taken += after.inUse(t);
            for (uint32_t t = 0; t < before.slotCount(); ++t)
                if (before.inUse(t) && !after.inUse(t)) freed.push_back(t);
            const uint32_t grown = after.slotCount() - before.slotCount();
            const uint32_t left = free_before - taken;
            bool ok = (grown == 0 || taken == free_before) && after.free_slots.size() == left + freed.size();
            for (uint32_t k = 0; ok && k < left; ++k) ok = after.free_slots[k] == before.free_slots[k];
            std::vector<uint32_t> pushed(after.free_slots.begin() + std::min<size_t>(left, after.free_slots.size()), after.free_slots.end());
            std::sort(pushed.begin(), pushed.end());
            ok = ok && pushed == freed;
            for (uint32_t t = before.slotCount(); ok && t < after.slotCount(); ++t) ok = after.inUse(t);
            if (!ok) UNSCOPED_INFO("round " << round << " broke the slot rule");
            rule = rule && ok;
            appended += grown;
            taken_total += taken;
            before = after;
        };
        const ddt::TetParallelStats stats = ddt::optimizeTetMeshParallel(mesh, second, options);
        CHECK(rule);
        CHECK(ddt::checkTetMesh(mesh) == "");
        CHECK(stats.flipsOf(FlipKind::two_three) > 0);
        CHECK(mesh.tetCount() == initial_slots + stats.flipsOf(FlipKind::two_three) - stats.flipsOf(FlipKind::three_two));
        if (weight == TetWeight::variance) {  // face_scf makes few 2–3 and 3–2 flips here
            CHECK(stats.flipsOf(FlipKind::three_two) > 0);
            CHECK(appended > 0);
            CHECK(taken_total > 0);
        }
    }
}

TEST_CASE("tet parallel: deterministic, and the evaluation list only saves work", "[tet-parallel]") {
    const ddt::TetCostField fields[] = {sphereField(8, 2.5), randomField({6, 5, 6}, 5, 3)};
    for (const ddt::TetCostField& field : fields)
        for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
            INFO(ddt::tetWeightName(weight));
            ddt::TetParallelOptions options;
            options.weight = weight;
            ddt::TetMesh first = ddt::kuhnTetMesh(field.size), second = first, everything = first;
            const ddt::TetParallelStats a = ddt::optimizeTetMeshParallel(first, field, options);
            const ddt::TetParallelStats b = ddt::optimizeTetMeshParallel(second, field, options);
            CHECK(sameMesh(first, second));
            CHECK(a.flips == b.flips);
            CHECK(a.rounds == b.rounds);
            CHECK(a.evaluated == b.evaluated);
            CHECK(a.cost_after == b.cost_after);
            // Every tet evaluated in every round: the same candidates, so the same rounds.
            options.evaluate_all = true;
            const ddt::TetParallelStats all = ddt::optimizeTetMeshParallel(everything, field, options);
            CHECK(sameMesh(first, everything));
            CHECK(all.flips == a.flips);
            CHECK(all.rounds == a.rounds);
            CHECK(all.candidates == a.candidates);
            CHECK(all.cost_after == a.cost_after);
            CHECK(all.evaluated > a.evaluated);
            // A second run finds nothing to do.
            options.evaluate_all = false;
            ddt::TetMesh again = first;
            const ddt::TetParallelStats second_run = ddt::optimizeTetMeshParallel(again, field, options);
            CHECK(second_run.flipCount() == 0);
            CHECK(second_run.rounds == 1);
            CHECK(sameMesh(again, first));
        }
}

TEST_CASE("tet parallel: the final cost against the serial Lawson's", "[tet-parallel]") {
    // Both stop at a local optimum of the same flips, reached in different orders, so neither
    // bounds the other; in 2-D the parallel rules ended 4–6 % from serial, either side. The
    // bound here is that observation with room, not a theorem: a rule that left much of the
    // serial gain behind (a broken selection, a lost active tet) lands far outside it.
    struct Case {
        const char* name;
        ddt::TetCostField field;
    };
    const Case cases[] = {{"sphere", sphereField(12, 4.0)}, {"slanted plane", slantedPlaneField(10)}};
    for (const Case& c : cases)
        for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
            ddt::TetMesh parallel_mesh = ddt::kuhnTetMesh(c.field.size), serial_mesh = parallel_mesh;
            ddt::TetParallelOptions parallel_options;
            parallel_options.weight = weight;
            const ddt::TetParallelStats parallel = ddt::optimizeTetMeshParallel(parallel_mesh, c.field, parallel_options);
            ddt::TetLawsonOptions serial_options;
            serial_options.weight = weight;
            const ddt::TetLawsonStats serial = ddt::optimizeTetMeshSerial(serial_mesh, c.field, serial_options);
            const double ratio = parallel.cost_after / serial.cost_after;
            WARN(c.name << ", " << ddt::tetWeightName(weight) << ": parallel/serial final cost " << ratio << " ("
                        << parallel.cost_after << " / " << serial.cost_after << "), " << parallel.rounds << " rounds, "
                        << parallel.flipCount() << " flips vs " << serial.iterations << " iterations, "
                        << serial.flipCount() << " flips");
            CHECK(parallel.cost_after < parallel.cost_before);
            CHECK(ratio > 0.9);
            CHECK(ratio < 1.1);
        }
}
