// Resampling a tetrahedral mesh (core/volume/tet_resample.h) on a Vulkan device: the kernel
// glsl/volume/tet_resample.comp, one invocation per tet, equal to core's resampleTetsInto bit
// for bit (the same exact integer tests and the same double operations, in the same order).
//
// Which tets the device resamples. Core tests a tet in int64 while 6 · Ex · Ey · Ez < 2^62 and
// in __int128 beyond; GLSL has no 128-bit integers, and llvmpipe ends an invocation's loops
// after 65 535 trips. So the kernel defers a tet to core (resampleTetSlotsInto, on the host
// after the device) when the int64 bound fails or its box of samples takes more than
// kTetResampleMaxBoxTrips loop trips (rows plus samples). Bricks would not help the bound: it
// holds per tet, on coordinate differences. At ×2 no tet of a Kuhn mesh comes near either: a
// Kuhn tet needs mx · my · mz ≥ 2^56 output voxels to fail the bound, ×30 per axis to fail the
// trips; a flipped tet spans a few voxels.
//
// Memory. The device holds the slots' vertices (16 bytes a slot), the values (4 bytes a vertex),
// one bit a slot for the deferred tets, and the output in slabs of at most `slab_voxels` (whole
// x rows of the window, as many y rows and z planes as fit), each copied into `out` after its
// dispatch.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "context.h"
#include "tet_mesh.h"
#include "tet_resample.h"
#include "volume/tet_resample_layout.h"

namespace ddt {

struct TetResampleDeviceOptions {
    uint64_t slab_voxels = uint64_t(1) << 24;  // output voxels per slab (64 MiB of floats)
    uint32_t max_box_trips = kTetResampleMaxBoxTrips;
    uint32_t narrow_log2 = kTetResampleNarrowLog2;  // tests lower both to defer tets on purpose
};

struct TetResampleDeviceReport {
    uint32_t slabs = 0;
    uint32_t deferred = 0;      // tets resampled by core on the host
    uint64_t device_bytes = 0;  // device memory the resampling held
};

// Why the device cannot resample the mesh into the window ("" if it can): too many slots or
// vertices for a texel buffer, or one output row longer than a slab.
std::string tetResampleDeviceProblem(const VulkanContext& context, const TetMesh& mesh, const TetResampleWindow& window,
                                     const TetResampleDeviceOptions& options = {});

// resampleTetsInto on the device: the window's output voxels into `out` (the whole output,
// window.new_size voxels, x fastest). Throws std::invalid_argument when
// tetResampleDeviceProblem names a problem.
void resampleTetsVulkan(VulkanContext& context, const TetMesh& mesh, const std::vector<float>& values,
                        const TetResampleWindow& window, float* out, const TetResampleDeviceOptions& options = {},
                        TetResampleDeviceReport* report = nullptr);

}  // namespace ddt
