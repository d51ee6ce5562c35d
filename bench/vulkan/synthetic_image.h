// The Vulkan bench's default input: a deterministic 8-bit RGB image of any size with what
// drives the optimisation on photos, at a fixed scale in pixels, so that every size has the
// same density of features (as mirrored photos do):
//   - smooth gradients: each channel a linear ramp across the image;
//   - sharp edges: in every 96-pixel cell a disc of radius 12 to 35 pixels in a flat colour,
//     and thin diagonal lines (slope −1/2, every 128 pixels along x, 3 pixels wide);
//   - texture: in a quarter of the cells (by hash) a fine 4-pixel checkerboard, ±0.08;
//   - noise: ±0.02 everywhere, from an integer hash of the position.
// Integer arithmetic decides every edge and noise value, so the image is the same on every
// machine; values are rounded to 8-bit levels (sample type UInt8).
#pragma once

#include <cstdint>

#include "image.h"

namespace ddt {

Image syntheticImage(uint32_t width, uint32_t height);

}  // namespace ddt
