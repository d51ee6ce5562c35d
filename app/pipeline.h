// Runs a batch with its three stages overlapped, like the other upscalers' -j load:proc:save:
// one thread decodes the next image while the device works on the current one and another
// thread encodes the rows already rendered, of this image or the previous one. The device is
// used from the calling thread only.
#pragma once

#include <functional>
#include <vector>

#include "backend.h"
#include "batch_plan.h"
#include "reporter.h"
#include "settings.h"
#include "upscale_job.h"

namespace ddt {

// Rendered rows in flight between the process and write stages, over all images: enough for
// several bands (core's render bands are far smaller), and a small image's whole output, so
// that the next image's optimization overlaps its encoding; not enough to matter beside the
// process's own size. Since a strip's tiles render in one parallel loop the renderer gets
// ahead of the encoder: 48 MiB filled up and took the photo ×4 to 276 MiB at its peak; with
// 24 MiB it peaks at 260 MiB for 1.02 × the wall time (farm-bench, 7 pairs; 0.95–1.03).
inline constexpr uint64_t kBandBudgetBytes = uint64_t(24) << 20;

// Magnifies every Ready image task (volumes go through app/volume/); failures are reported and the batch goes on. `backend` is called
// when the first image has been read (so that a bad input is reported without starting a
// device); when it returns null (no device, already reported) the run stops. `on_done` runs
// after each image is written (on the writing thread).
void runPipeline(const std::vector<ImageTask>& tasks, const Settings& settings,
                 const std::function<Backend*()>& backend, Reporter& reporter,
                 const std::function<void(const ImageJob&)>& on_done);

}  // namespace ddt
