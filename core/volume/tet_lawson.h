// The serial generalized Lawson optimization of a tetrahedral mesh (Tóth et al., Sect. 4 and
// Fig. 7): the quality reference for any parallel rule.
//
// - the active list starts as every tet in slot order; a tet stands for its 4 faces and 6
//   edges, the sites of the four flips (core/volume/tet_flips.h).
// - each active tet still in use is tested once per iteration: its best flip worth applying
//   (bestFlipAt: the largest gain above kTetFlipGainThreshold · gain_scale) is applied.
// - the candidate list collects, each once, the tets a flip touched: the new tets' slots and,
//   for face_scf, their face-neighbours (whose faces now border new tets: their sites' gains
//   changed). A variance gain reads only its region, every site of which belongs to a new
//   tet, so variance queues the new tets alone. Like Fig. 7's line 17, a tet still waiting in
//   this iteration's active list is not queued again: it will be tested with the changes.
// - the next iteration tests the candidates in slot order; the run ends after an iteration
//   that applied no flip. Fig. 7 stops when the cost stops falling, the same test in exact
//   arithmetic (every applied flip lowers the exact cost by more than the threshold); a
//   computed total of millions of terms rounds by more than one flip's gain, so the loop
//   counts flips instead of comparing totals.
// Deterministic: fixed orders throughout, no threads.
#pragma once

#include <array>
#include <cstdint>
#include <functional>

#include "tet_cost.h"
#include "tet_flips.h"
#include "tet_mesh.h"

namespace ddt {

struct TetLawsonOptions {
    TetWeight weight = TetWeight::variance;
    // Safety cap on iterations; reaching it is reported (TetLawsonStats::capped).
    uint32_t max_iterations = 100000;
    // Called after every iteration with the mesh and its cached total cost, for tests.
    std::function<void(uint32_t iteration, const TetMesh& mesh, double cost)> after_iteration;
};

struct TetLawsonStats {
    double cost_before = 0.0;
    double cost_after = 0.0;  // equals meshCost(mesh, field, weight) bit for bit
    std::array<uint64_t, kFlipKindCount> flips{};  // by FlipKind
    uint32_t iterations = 0;  // including the last one, which applied no flip
    bool capped = false;      // stopped by max_iterations before a local optimum

    uint64_t flipCount() const { return flips[0] + flips[1] + flips[2] + flips[3]; }
    uint64_t flipsOf(FlipKind kind) const { return flips[uint32_t(kind)]; }
};

TetLawsonStats optimizeTetMeshSerial(TetMesh& mesh, const TetCostField& field, const TetLawsonOptions& options = {});

}  // namespace ddt
