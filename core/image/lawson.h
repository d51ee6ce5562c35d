// The serial reference optimizer: Lawson's local optimization (paper Fig. 3). Sweeps over
// the edges in id order and flips every edge whose gain exceeds kFlipGainThreshold, until a
// sweep flips nothing. Every backend reports the same figures (OptimizeStats).
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>

#include "cost.h"
#include "mesh.h"

namespace ddt {

struct OptimizeStats {
    double cost_init = 0.0;
    double cost_final = 0.0;
    uint64_t flips = 0;
    uint32_t iterations = 0;  // serial: sweeps; parallel: candidate/select/flip iterations
    uint64_t rounds = 0;      // parallel only: accept/reject rounds over all iterations
    uint32_t max_rounds_in_iteration = 0;  // parallel only
    uint64_t dispatches = 0;  // Vulkan only: kernel dispatches recorded
    double device_ms = 0.0;   // Vulkan only: optimize time from GPU timestamps
    bool capped = false;      // stopped by a safety cap before reaching a local optimum

    // Table 1's "improvement": cost-init / cost-final × 100 %.
    double improvement() const { return cost_final > 0.0 ? 100.0 * cost_init / cost_final : 0.0; }
};

// Adds a tile's statistics to the run's (overlaps counted in each tile).
inline void addStats(OptimizeStats& total, const OptimizeStats& tile) {
    total.cost_init += tile.cost_init;
    total.cost_final += tile.cost_final;
    total.flips += tile.flips;
    total.iterations += tile.iterations;
    total.rounds += tile.rounds;
    total.max_rounds_in_iteration = std::max(total.max_rounds_in_iteration, tile.max_rounds_in_iteration);
    total.dispatches += tile.dispatches;
    total.device_ms += tile.device_ms;
    total.capped = total.capped || tile.capped;
}

struct LawsonOptions {
    // The cost the flips lower (core/image/cost.h; `--cost` on the command line).
    CostFunction cost = CostFunction::sederberg;
    // Safety cap on sweeps. Real images need a few dozen; reaching it is reported.
    uint32_t max_sweeps = 100000;
    // Called after every sweep, for tests that watch the cost.
    std::function<void(uint32_t sweep, const Mesh& mesh)> after_sweep;
};

OptimizeStats optimizeSerial(Mesh& mesh, const CostField& field, const LawsonOptions& options = {});

}  // namespace ddt
