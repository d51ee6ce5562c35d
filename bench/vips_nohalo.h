// libvips' Nohalo interpolator (Racette, Robidoux et al.), a peer of Lanczos and DDT in the
// protocol tables: edge-adaptive subdivision with no halo by construction.
//
// It runs through vips_affine with the scale as the matrix and the input displacement
// idx = idy = 0.5 − 0.5 / s, so that output pixel X samples the input at (X + 0.5) / s − 0.5
// exactly as ddtup's renderer (and OIIO's resize) do; without it the output is shifted by a
// quarter of an input pixel at ×2, which costs about a dB. The bench measures the shift on a
// ramp (ramp_alignment.h) instead of trusting the convention.
#pragma once

#include <cstdint>

#include "image.h"

namespace bench {

// `input` (grey or RGB, values in [0, 1]) magnified to width × height by Nohalo, in float,
// borders extended by copying the edge pixels.
ddt::Image magnifyWithNohalo(const ddt::Image& input, uint32_t width, uint32_t height);

}  // namespace bench
