// The volume pipeline's core, shared by ddtup and the bench: tetrahedralize (Kuhn), optimize by
// bistellar flips (the serial generalized Lawson, core/volume/tet_lawson.h), resample every
// output voxel in its tet (core/volume/tet_resample.h, or a device's kernel equal to it) — the
// whole volume as one mesh, or in bricks with overlap, as 2-D images go in tiles.
//
// Bricks. Along each axis the input's index range [0, n − 1] is cut at multiples of the brick
// side into cores [c_k, c_k+1) (the last one closed). Output voxel i' belongs to the brick whose
// cores hold its sample point along every axis (core/volume/volume.h's mapping, clamped to the
// box), so every output voxel is resampled exactly once. A brick's mesh covers its cores plus
// `margin` voxels on each side (within the volume) and is optimized on its own, with values
// normalized by the whole volume's range, so that a flip means the same in every brick. The
// margin lets the flips near a core's side see what lies beyond it; without it they would see a
// box side, where the whole volume has none. Results near core sides may still differ from the
// whole volume's (as tiled images do), by flips that reach further than the margin.
//
// Memory. One mesh costs about 6 tets × 80 bytes (vertices, neighbours, cached costs) ≈ 500
// bytes per voxel (measured: 1 GB at 128³); a brick of side 128 with margin 8 about 1.2 GB.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "tet_cost.h"
#include "tet_lawson.h"
#include "tet_resample.h"
#include "volume.h"

namespace ddt {

// The largest volume optimized as one mesh, in voxels (about 2 GB); larger ones go in bricks.
constexpr uint64_t kMaxVoxelsInOneMesh = uint64_t(1) << 22;
// The automatic brick side and the margin, in input voxels.
constexpr uint32_t kDefaultBrickSide = 128;
constexpr uint32_t kBrickMargin = 8;

// Flips one mesh to a local optimum of the field's cost with the weight. core/ has the serial
// generalized Lawson; the app passes a Vulkan device's parallel rule (core/ links no Vulkan).
// The field is the optimizer's to release (the caller has no more use for it), and the mesh may
// come back without its neighbours (the resampling reads only the vertices).
using TetOptimizer = std::function<TetLawsonStats(TetMesh&, TetCostField&&, TetWeight)>;
// Resamples one mesh's window into the whole output (resampleTetsInto's contract); the app
// passes a Vulkan device's kernel, equal to core's bit for bit.
using TetResampler = std::function<void(const TetMesh&, const std::vector<float>&, const TetResampleWindow&, float*)>;

struct VolumeMagnifyOptions {
    TetWeight weight = TetWeight::variance;
    TetOptimizer optimize;  // empty: optimizeTetMeshSerial
    TetResampler resample;  // empty: resampleTetsInto
    // The brick side in input voxels; 0: one mesh up to kMaxVoxelsInOneMesh, else bricks of
    // kDefaultBrickSide.
    uint32_t brick_side = 0;
    uint32_t margin = kBrickMargin;
};

struct VolumeMagnifyStats {
    uint32_t bricks = 0;
    uint64_t tets_before = 0, tets_after = 0;  // summed over the bricks (margins included)
    TetLawsonStats lawson;                     // summed over the bricks (iterations: the most)
    double optimize_s = 0.0;                   // build the meshes and flip
    double resample_s = 0.0;
};

// The bricks of a volume of `size` voxels magnified to new_size (side 0: one brick, the whole
// volume): each one's mesh (its vertex_offset and the vertices' extent, `mesh_size`) and the
// output voxels it resamples. The windows partition the output.
struct VolumeBrick {
    std::array<uint32_t, 3> mesh_size{};
    TetResampleWindow window;
};
std::vector<VolumeBrick> volumeBricks(const std::array<uint32_t, 3>& size, const std::array<uint32_t, 3>& new_size,
                                      uint32_t side, uint32_t margin);

// The volume magnified to new_size voxels (x fastest, physical values).
std::vector<float> magnifyVolumeValues(const Volume& volume, const std::array<uint32_t, 3>& new_size,
                                       const VolumeMagnifyOptions& options, VolumeMagnifyStats& stats);

}  // namespace ddt
