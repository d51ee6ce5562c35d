// One volume's way through a run: read, magnify (core/volume/volume_magnify.h: tetrahedralize,
// optimize by bistellar flips, resample; in bricks when large or --tile asks), write, and the
// middle slices when asked. Volumes run one after another; the flips and the resampling on the
// engine --backend chooses (app/backend_factory.h: the CPU, or a Vulkan device), the rest on the CPU.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "batch_plan.h"
#include "reporter.h"
#include "settings.h"
#include "volume_magnify.h"

namespace ddt {

// What --stats prints for a volume.
struct VolumeReport {
    std::array<uint32_t, 3> in{};
    std::array<uint32_t, 3> out{};
    VolumeMagnifyStats stats;
    bool on_device = false;  // the flips (the parallel rule) and the resampling ran on a Vulkan device
    double read_s = 0.0;   // read and check the file
    double write_s = 0.0;  // the output file and the slices
};

// The largest output, in voxels: the output is held whole, as floats (8 GiB at the limit).
inline constexpr uint64_t kMaxOutputVoxels = uint64_t(1) << 31;

// Magnifies every Ready volume task of `tasks`, reporting each; failures are reported and the
// batch goes on. `on_done` runs after each volume is written.
// Returns false when the engine could not be made (no device; reported as fatal).
bool runVolumeTasks(const std::vector<ImageTask>& tasks, const Settings& settings, Reporter& reporter,
                    const std::function<void(const ImageTask&, const VolumeReport&)>& on_done);

}  // namespace ddt
