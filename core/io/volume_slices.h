// Previews of a volume: the three planes through its middle voxel as 8-bit grey PNG files.
//
// - axial:    the x–y plane at z = nz / 2; x to the right, y downward (as scanners store slices)
// - coronal:  the x–z plane at y = ny / 2; x to the right, z upward
// - sagittal: the y–z plane at x = nx / 2; y to the right, z upward
// Planes of the index frame, one pixel per voxel: neither the affine's directions nor
// anisotropic spacing are applied (a 0.5 × 0.5 × 2.5 mm CT's coronal slice looks squashed
// five times along z). Values are windowed linearly from the volume's whole data range
// [min, max] to [0, 255], rounded to the nearest level; a constant volume is all 0.
#pragma once

#include <string>
#include <vector>

#include "volume.h"

namespace ddt {

// Writes `folder`/`stem`-axial.png, -coronal.png and -sagittal.png, each through a temporary
// file renamed into place (output_file.h). Returns their paths. Throws UserError("PATH: reason").
std::vector<std::string> writeMiddleSlices(const Volume& volume, const std::string& folder, const std::string& stem);

}  // namespace ddt
