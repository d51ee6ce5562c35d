// Times one magnification on a backend stage by stage, as the app runs them: prepare (build
// the mesh, upload), optimize, optionally the consistent reconstruction, and render into
// memory in the app's bands (no file is written).
#pragma once

#include <vector>

#include "backend.h"

namespace ddt {

struct StageTimes {
    OptimizeStats stats;
    double prepare_s = 0.0, optimize_s = 0.0, reconstruct_s = 0.0, render_s = 0.0;

    double total_s() const { return prepare_s + optimize_s + reconstruct_s + render_s; }
};

StageTimes timeStages(Backend& backend, const Image& image, OutputSize out, bool reconstruct);

// The median of each stage's time and of OptimizeStats::device_ms; the other stats are the
// first run's (the optimizers are deterministic).
StageTimes medianStages(const std::vector<StageTimes>& runs);

double median(std::vector<double> values);

}  // namespace ddt
