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

// Rendered rows in flight between the process and write stages, over all images: several
// bands, and a small image's whole output, so that the next strip's or image's optimisation
// overlaps their encoding. What is in flight when the next strip's tiles are shaped adds to
// the run's peak, and the encoder lags most at large scales: with 24 MiB the 512² photo
// peaked at 79–98 MiB at ×16 against 77–90 at ×8; with 12 MiB, and the bands sent as the
// writer's codes, 79 against 76–77 (/usr/bin/time, 3 runs each), at the same wall times.
inline constexpr uint64_t kBandBudgetBytes = uint64_t(12) << 20;

// Magnifies every Ready image task (volumes go through app/volume/); failures are reported and the batch goes on. `backend` is called
// when the first image has been read (so that a bad input is reported without starting a
// device); when it returns null (no device, already reported) the run stops. `on_done` runs
// after each image is written (on the writing thread).
void runPipeline(const std::vector<ImageTask>& tasks, const Settings& settings,
                 const std::function<Backend*()>& backend, Reporter& reporter,
                 const std::function<void(const ImageJob&)>& on_done);

}  // namespace ddt
