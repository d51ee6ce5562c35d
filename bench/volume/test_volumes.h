// The volume bench's synthetic inputs: deterministic functions of position sampled on a voxel
// grid, optionally with seeded Gaussian noise, and the area averaging that shrinks them before
// the methods magnify them back.
//
// Every volume has unit spacing, voxel (0, 0, 0) at the world origin (an identity affine) and
// float samples. Partial volume: a voxel's value is the mean of the function over
// kSubsamples³ points spread evenly over its cube [x − 0.5, x + 0.5] × … (a box filter of the
// continuous scene), so interfaces are anti-aliased as a scanner's voxels would be.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "volume.h"

namespace bench {

constexpr uint32_t kSubsamples = 4;

enum class TestVolumeKind {
    // The paper's test (Tóth et al., Sec. 6, Fig. 9: "a sphere embedded into a cube", 32³): 1 inside
    // a sphere at the box's centre, 0 outside. The paper states no radius; ours is 0.3 of the
    // shortest side (9.6 voxels at 32³), well inside the box.
    sphere,
    // The 3-D Shepp–Logan head phantom with 10 ellipsoids, Kak & Slaney's table (test_volumes.cpp)
    // with the high-contrast intensities of Yu, Ye & Wang; values from 0 to 1.
    shepp_logan,
    // A smooth field (low-frequency sinusoids, amplitude 0.15 about 0.25) plus a step of 0.5
    // across the slanted plane x + 2y + 3z = c through the box's centre: an interface that no
    // grid axis or Kuhn face is aligned with.
    slanted_interface,
};

// "sphere", "shepp-logan", "slanted-interface".
std::string testVolumeName(TestVolumeKind kind);

// The kind's volume at `size` (each side at least 2), plus Gaussian noise of standard deviation
// noise_sigma (0: none) drawn from `seed`.
ddt::Volume makeTestVolume(TestVolumeKind kind, const std::array<uint32_t, 3>& size, double noise_sigma = 0.0,
                           uint64_t seed = 1);

// Adds independent Gaussian noise of standard deviation sigma to every voxel: the same values for
// the same seed on every platform (a 64-bit Mersenne Twister and the Box–Muller transform, not
// std::normal_distribution, whose algorithm the standard leaves open).
void addGaussianNoise(ddt::Volume& volume, double sigma, uint64_t seed);

// Each output voxel the mean of factor³ input voxels (factor 2 or 4; each side a multiple of
// it), the affine moved to match (ddt::resampledAffine): the bench's shrinking, which the
// methods' magnification by the same factor undoes on the same voxel-centre mapping.
ddt::Volume areaAverageVolume(const ddt::Volume& volume, uint32_t factor);

}  // namespace bench
