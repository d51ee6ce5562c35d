// One volume's way through a run: read, tetrahedralize (core/volume/tet_mesh.h), optimize by
// bistellar flips (the serial generalized Lawson), resample onto the magnified grid, write,
// and the middle slices when asked. Volumes run one after another, on the CPU: their Vulkan
// kernels are not written yet, and --backend auto says so.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "batch_plan.h"
#include "reporter.h"
#include "settings.h"
#include "tet_lawson.h"

namespace ddt {

// What --stats prints for a volume.
struct VolumeReport {
    std::array<uint32_t, 3> in{};
    std::array<uint32_t, 3> out{};
    uint64_t tets_before = 0, tets_after = 0;
    TetLawsonStats stats;
    double read_s = 0.0;      // read and check the file
    double optimize_s = 0.0;  // build the tetrahedral mesh and optimize it
    double resample_s = 0.0;  // every output voxel in its tetrahedron
    double write_s = 0.0;     // the output file and the slices
};

// The volumes' largest input, in voxels, while a volume is optimized as one mesh: about 300
// bytes per voxel (6 tets of vertices, neighbours and cached costs), 5 GB at 256³.
inline constexpr uint64_t kMaxVoxelsInOneMesh = uint64_t(1) << 24;
// The largest output, in voxels: the output is held whole, as floats (8 GiB at the limit).
inline constexpr uint64_t kMaxOutputVoxels = uint64_t(1) << 31;

// Magnifies every Ready volume task of `tasks`, reporting each; failures are reported and the
// batch goes on. `on_done` runs after each volume is written.
void runVolumeTasks(const std::vector<ImageTask>& tasks, const Settings& settings, Reporter& reporter,
                    const std::function<void(const ImageTask&, const VolumeReport&)>& on_done);

}  // namespace ddt
