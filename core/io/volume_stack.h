// A volume from 2-D slices, read only when the user asks for it (--stack), so that a folder or a
// multi-page TIFF keeps meaning a batch or one image otherwise: a folder of images (every file
// with an image format's extension, hidden files passed over, slice k the k-th name in sorted
// order) or a multi-page TIFF (slice k the k-th page). Every slice grey, of one size and one
// sample type; 8- and 16-bit samples keep their integer levels (0–255, 0–65535) as values, half
// and float samples their values. There is no geometry in slices: the volume has unit spacing
// and its first voxel at the origin.
#pragma once

#include <string>

#include "volume.h"

namespace ddt {

// Throws UserError("PATH: reason"): not a folder or TIFF, fewer than 2 slices, a colour or
// alpha slice, slices of different sizes or sample types, too many voxels (volume.h's limits),
// and whatever reading a slice throws.
Volume readImageStack(const std::string& path);

}  // namespace ddt
