// How close a magnified-back volume is to the original (the volume bench's scores).
//
// - data range: max − min of the original's values, the peak of PSNR (volumes have no fixed
//   white level as 8-bit images have).
// - PSNR (dB): 10 · log10(range² / MSE), MSE the mean of (original − result)² over all voxels;
//   +∞ for identical volumes.
// - isosurface distance (voxels of the original): the mean distance between the surfaces where
//   the two volumes cross `level` (the bench uses the middle of the original's range), both
//   taken as the isosurface of the volume's trilinear interpolant and sampled as points, with no
//   marching cubes. Query points: on every grid edge between two neighbouring voxels whose values
//   lie on either side of the level (one < level, the other ≥ level), where linear interpolation
//   along the edge meets it. Target points: the same on the edges of a grid
//   kIsosurfaceSubdivision times finer, in the cells the surface passes through, so that the
//   nearest target lies within a small fraction of a voxel of the nearest surface point (with
//   targets as sparse as the queries, about one per voxel, two parallel planes 0.3 voxels apart
//   measured 0.41; with ×4 targets, 0.32). The score is the symmetric mean
//   (mean over A's queries of the distance to B's nearest target + the same from B to A) / 2,
//   the nearest targets found in a uniform grid hash of one-voxel cells. A result of another size
//   is placed in the original's index frame by the voxel-centre mapping (ddt::inputIndexOf).
//   NaN when either volume never crosses the level.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "volume.h"

namespace bench {

double dataRange(const ddt::Volume& original);

// `result` the same size as `original`.
double volumePsnr(const ddt::Volume& original, const ddt::Volume& result, double range);

constexpr uint32_t kIsosurfaceSubdivision = 4;

// The isosurface points of `volume` at `level` on the edges of its grid (subdivision 1) or of a
// grid `subdivision` times finer (its trilinear interpolant's values), in the index frame of a
// volume of `frame_size` voxels over the same box (volume.size itself for its own frame).
std::vector<std::array<double, 3>> isosurfacePoints(const ddt::Volume& volume, double level,
                                                    const std::array<uint32_t, 3>& frame_size, uint32_t subdivision = 1);

// The mean distance from each point of `from` to the nearest point of `to` (NaN if either is
// empty).
double meanNearestDistance(const std::vector<std::array<double, 3>>& from, const std::vector<std::array<double, 3>>& to);

// The symmetric mean isosurface distance above, in voxels of `original`.
double isosurfaceDistance(const ddt::Volume& original, const ddt::Volume& result, double level);

}  // namespace bench
