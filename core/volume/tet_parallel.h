// The parallel flip rule for tetrahedral meshes: the serial generalized Lawson's flips
// (core/volume/tet_lawson.h, the quality reference) decided in rounds, each a step that a
// device runs with one invocation per tet or per candidate, in three steps as the 2-D kernels
// (glsl/image/candidates.comp, select.comp, flip.comp): candidates, a conflict-free selection, flips.
// This is the CPU version; the Vulkan kernels (glsl/volume/, compute/volume/tet_device.h)
// compute the same rounds bit for bit.
//
// Words (core/volume/tet_mesh.h's glossary, and tet_flips.h's plans):
// - a flip's owner: the smallest slot among its region's tets. Every flip has exactly one,
//   whichever of its tets it is found from, and the owner's view of it is the canonical one
//   (the plan made from the owner: its ring starts there, so its new tets, the 4–4's diagonal
//   tie and the gain's order of summation are fixed).
// - a tet's best owned flip: bestOwnedFlipAt below, bestFlipAt's rule over the sites it owns.
// - the key of a candidate (tetFlipKey): the high 32 bits of its gain's double, then
//   tetTieWord(owner) (glsl/volume/tet_layout.h), a fixed bijection of the owner's slot; the
//   larger key wins.
//   * A positive double's bits compare as its value, so the high word is the gain rounded
//     towards zero to 21 significant bits: monotone, exact on every device (a bit extraction,
//     no rounding mode), and wide enough for any unit (a float32 would flush the gains of a
//     volume in metres of 2^-30 to zero). Gains within a factor 1 + 2^-20 tie.
//   * Ties go to the tie word, which is unique per owner, so keys are unique. Not the owner's
//     slot itself: equal gains are common (symmetric volumes, a plane at a constant slope), and
//     slot order follows the grid, so a chain of equal conflicting candidates along a row
//     would be decided one per round from its low end; a mixed order decides such chains in a
//     few rounds (the simplification's tieOrder, glsl/simplify/simplify_layout.h, for the
//     same reason).
//
// A round:
//  (a) candidates: each tet to evaluate proposes its best owned flip worth applying (gain >
//      kTetFlipGainThreshold · gain_scale), if any.
//  (b) selection: claim[r] = the largest key among the candidates whose read set
//      (FlipPlan::readSet: region, then hull tets) holds r; a candidate is accepted iff
//      claim[r] equals its key for every r of its read set. Order-independent (a maximum).
//  (c) flips: the accepted ones, in owner order, with this slot rule: the k-th accepted 2–3
//      (k = 0, 1, … in owner order) takes free_slots[F − 1 − k] while k < F, F the free
//      slots at the round's start (the top of the stack first), else the new slot
//      slotCount + k − F appended; after all flips, the slots the 3–2 flips freed are pushed
//      in owner order. Both ranks are prefix sums over the accepted flips in owner order,
//      which is how the kernels compute them. The cost cache (TetCosts) follows.
//  (d) the next round's tets to evaluate: the owners of the flippable, not all-flat sites
//      (faces with a tet across; interior edges of degree 3 or 4; boundary edges of degree 2)
//      of the active tets — the new tets' slots and, for face_scf, their face-neighbours
//      (tet_lawson's candidate list) — and the owners of this round's unaccepted candidates
//      whose read sets meet an accepted one's. The other unaccepted candidates are carried
//      over to the next round as they are (unless their owners are evaluated anyway): nothing
//      their plans read has changed. In smooth volumes most candidates lose several rounds in
//      a row (the bench's slanted interface at 32³, variance: 1.8 M candidates for 79 k flips),
//      and carrying them cuts the evaluations there from 2.46 M to 1.09 M.
//      The run ends after a round that accepts nothing. Before the first round, the active tets
//      are those that are not flat: a site whose tets are all flat has gain 0, so every site
//      worth looking at holds one (most of a CT or a synthetic phantom is flat).
//
// Why accepted flips never change what another accepted flip's gain (or plan) read:
// - What a plan reads (tet_flips.cpp): the region's records (the ring walk, the new tets, the
//   faces' matching) and the hull tets' neighbour entries (hull_back); its gain reads, with
//   the variance weight, the region's cached costs and contents only — a tet's cost depends
//   on its own four vertices — and with face_scf the gradients and contents of the region and
//   of the hull tets, since a tet's face_scf cost depends on its face-neighbours' gradients.
//   All of it lies in readSet (region ∪ hull tets) for both weights.
// - What applying a plan writes: the region's records (rewritten or freed), one free slot
//   (2–3), in each hull tet the one neighbour entry pointing into the region, and in the
//   cost cache the region's slots and (face_scf) the hull tets' costs: all in readSet, but for
//   the free slot, which no read set holds, and which the slot rule gives to one flip only.
// - Two accepted candidates a ≠ b have disjoint read sets: a tet r in both would have
//   claim[r] = key(a) = key(b), but keys are unique (one candidate per owner).
// So each accepted flip writes nothing another one read: every plan is still exact after any
// of the others, applying them one by one in owner order is applying them together, and the
// exact cost falls by the sum of their gains. The variance weight would need only the regions
// disjoint for its gains, but not for its plans: a plan names its hull tets' slots and their
// back-link entries, which a neighbouring flip would rewrite, so both weights claim readSet.
//
// Why the run ends at a local optimum (no tet owns a flip worth applying — every flip has an
// owner, so no flip at all is worth applying as its owner sees it), with (d)'s short list:
// invariant — before each round's candidates, a tet left out of the evaluation owns no flip
// worth applying. A site's decision (legality, gain) reads only the records of its read set's
// tets; a tet is written by a round only when it is a new tet (or is freed), or when one
// neighbour entry of it is redirected, which matters to a site only where a new tet now lies
// across. So a site whose decision changed has a new tet in its region (then that new tet is
// active and lists the site's owner) or, for face_scf, a new tet across a region tet's face
// (then that region tet is a face-neighbour of a new tet, active, and lists it); new sites have
// a new tet in their region. A site unchanged was worth applying before only if its owner was
// a candidate: accepted (the owner's slot now holds a new tet, active) or not (listed, or carried
// over with the very plan it would make again: its read set is untouched and no site of its
// owner changed, else the owner is listed). Before the first round, every site not all flat
// holds a tet that is not flat, active then.
// Consequently the candidates of a round are exactly every tet's best owned flip worth applying:
// the list only saves work, and any larger list (evaluate_all) gives the same rounds.
//
// Deterministic: every step is a function of the mesh, in fixed orders. A round that has
// candidates accepts at least the one with the largest key, so the run ends.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <functional>
#include <optional>

#include "tet_cost.h"
#include "tet_flips.h"
#include "tet_mesh.h"
#include "volume/tet_layout.h"

namespace ddt {

struct TetParallelOptions {
    TetWeight weight = TetWeight::variance;
    // Safety cap on rounds; reaching it is reported (TetParallelStats::capped).
    uint32_t max_rounds = 100000;
    // Evaluate every tet in every round instead of (d)'s list: the same rounds (see above),
    // for tests.
    bool evaluate_all = false;
    // Called after every round with the mesh and its cached total cost, for tests.
    std::function<void(uint32_t round, const TetMesh& mesh, double cost)> after_round;
};

struct TetParallelStats {
    double cost_before = 0.0;
    double cost_after = 0.0;  // equals meshCost(mesh, field, weight) bit for bit
    std::array<uint64_t, kFlipKindCount> flips{};  // by FlipKind
    uint32_t rounds = 0;      // including the last one, which accepted nothing
    bool capped = false;      // stopped by max_rounds before a local optimum
    uint64_t evaluated = 0;   // tets evaluated, over all rounds
    uint64_t candidates = 0;  // candidates, over all rounds (the carried ones once a round)

    uint64_t flipCount() const { return flips[0] + flips[1] + flips[2] + flips[3]; }
    uint64_t flipsOf(FlipKind kind) const { return flips[uint32_t(kind)]; }
};

// The owner of a plan: its region's smallest slot.
uint32_t ownerOf(const FlipPlan& plan);

// The selection key of a candidate with gain `gain` (> 0) owned by `owner` (see above).
inline uint64_t tetFlipKey(double gain, uint32_t owner) {
    return (std::bit_cast<uint64_t>(gain) >> 32) << 32 | tetTieWord(owner);
}

// bestFlipAt restricted to the sites t owns: a face (2–3) whose tet across has a larger slot,
// an edge (3–2, 4–4, 2–2) whose ring's smallest slot is t. Same order of sites, same ties
// (the first), same skip of all-flat regions.
std::optional<FlipPlan> bestOwnedFlipAt(const TetMesh& mesh, const TetCosts& costs, uint32_t t);

// Calls `list(owner)` for the owner of each flippable site of t whose region is not all flat
// (faces with a tet across; interior edges of degree 3 or 4; boundary edges of degree 2), as
// step (d) lists them; an owner may come more than once.
void forEachSiteOwner(const TetMesh& mesh, const TetCosts& costs, uint32_t t, const std::function<void(uint32_t)>& list);

TetParallelStats optimizeTetMeshParallel(TetMesh& mesh, const TetCostField& field, const TetParallelOptions& options = {});

}  // namespace ddt
