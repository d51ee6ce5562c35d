#include "lawson.h"

namespace ddt {

OptimizeStats optimizeSerial(Mesh& mesh, const CostField& field, const LawsonOptions& options) {
    OptimizeStats stats;
    stats.cost_init = meshCost(mesh, field);
    bool flipped = true;
    while (flipped) {
        if (stats.iterations == options.max_sweeps) {
            stats.capped = true;
            break;
        }
        flipped = false;
        for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
            if (flipGainOf(mesh, field, e) > kFlipGainThreshold) {
                flipEdge(mesh, e);
                ++stats.flips;
                flipped = true;
            }
        }
        ++stats.iterations;
        if (options.after_sweep) options.after_sweep(stats.iterations, mesh);
    }
    stats.cost_final = meshCost(mesh, field);
    return stats;
}

}  // namespace ddt
