// The classic separable resamplers the volume bench compares the tetrahedral reconstruction
// with: trilinear, and tricubic Catmull–Rom (Keys' cubic convolution with a = −0.5; Keys,
// "Cubic convolution interpolation for digital image processing", IEEE TASSP 29(6), 1981).
//
// Both sample the input where the tetrahedral resampler does (core/volume/volume.h): output
// voxel i' at input index u = (i' + 0.5) · n / m − 0.5 per axis (ddt::inputIndexOf). Taps beyond
// the volume repeat its border voxel (edge replication), so trilinear equals the tetrahedral
// resampler's clamping at the border, and a constant volume stays constant. Separable: one pass
// per axis (x, then y, then z), each in double with float between passes (a rounding of
// 2^-24 relative, far below what the bench measures).
#pragma once

#include <array>
#include <cstdint>

#include "volume.h"

namespace bench {

enum class GridFilter { trilinear, catmull_rom };

// `volume` resampled to new_size voxels (each side at least 1), its affine moved to match
// (ddt::resampledAffine); the sample type is kept.
ddt::Volume resampleGrid(const ddt::Volume& volume, const std::array<uint32_t, 3>& new_size, GridFilter filter);

}  // namespace bench
