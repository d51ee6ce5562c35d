// The main job: read an image, triangulate, optimize, render and write it, timed in the
// paper's three stages.
#pragma once

#include <string>
#include <vector>

#include "backend.h"
#include "settings.h"

namespace ddt {

struct StageTimes {
    double init_s = 0.0;   // load + build the mesh (+ upload)
    double comp_s = 0.0;   // optimize
    double final_s = 0.0;  // render + save (the paper's time-final saved the mesh instead)
};

struct JobReport {
    OptimizeStats stats;
    StageTimes times;
    OutputSize out;
    std::vector<std::string> notes;  // one-line remarks for the user (e.g. depth changed)
};

// Throws UserError for bad input, output or settings.
JobReport runUpscaleJob(const Settings& settings);

// The output size the settings ask for, for an input of width × height.
OutputSize requestedOutputSize(const Settings& settings, uint32_t width, uint32_t height);

std::unique_ptr<Backend> makeBackend(const Settings& settings);

}  // namespace ddt
