// Timed runs of a DDT method in the paper's three stages (Sec. 6, Table 1):
// - time-init:  decode the low-resolution PNG held in memory + Backend::prepare (initial
//               mesh, and upload for a GPU backend);
// - time-comp:  Backend::optimize;
// - time-final: Backend::renderRows for every output row, into memory (no PNG encoding;
//               the paper's time-final saved the mesh instead).
// The backend is constructed once per measurement, before any timer (creating a device or
// pipelines is not one of the paper's stages); warm-up runs absorb first-use costs (caches,
// shader compilation) and are not reported. The stages are timed with steady_clock.
#pragma once

#include <cstdint>
#include <vector>

#include "lawson.h"
#include "memory_png.h"
#include "methods.h"
#include "upscale_job.h"

namespace bench {

struct DdtRun {
    ddt::OptimizeStats stats;
    ddt::StageTimes times;
};

struct DdtMeasurement {
    std::vector<DdtRun> runs;  // the timed runs, warm-ups excluded
    ddt::StageTimes median;    // the median of each stage over the runs

    // time-sum: the sum of the stage medians, as the paper's row sums its averages.
    double medianSum() const { return median.init_s + median.comp_s + median.final_s; }
};

// Runs `method` on `input` magnified to `out`, `warmups` + `repeats` times. With `output`,
// the last run renders into it (out.width × out.height × channels); without, rows are
// rendered in bands and dropped, so huge outputs fit in memory.
DdtMeasurement measureDdt(const DdtMethod& method, const PngInMemory& input, ddt::OutputSize out, uint32_t warmups,
                          uint32_t repeats, ddt::Image* output);

}  // namespace bench
