// An edge-directed interpolator as the classical state of the art among the protocol tables'
// peers: ICBI, iterative curvature-based interpolation (Giachetti & Asuni, "Real-time
// artifact-free image upscaling", IEEE TIP 20(10), 2011), written here from the paper's
// description (edge_directed.cpp gives the discrete form used).
//
// ICBI doubles an image on a "corner" grid: input pixel (i, j) lands on (2i, 2j) of a
// (2w − 1) × (2h − 1) grid. Each ×2 step fills the diagonal centres (2i + 1, 2j + 1) along the
// diagonal of lower second derivative, refines them by descending a local energy (curvature
// continuity, curvature enhancement, isophote smoothing), then fills and refines the remaining
// pixels the same way on the grid turned by 45°. Channels are interpolated independently.
//
// Factors: k = ⌈log2 s⌉ ×2 steps (at least one; ×2.5 runs two), then one separable
// Catmull-Rom resampling of the 2^k corner grid onto the requested size under ddtup's
// convention, output pixel X sampling the input at (X + 0.5) / s − 0.5, i.e. the corner grid
// at 2^k · ((X + 0.5) / s − 0.5), mirrored about the border pixels where that falls outside.
// At s = 2^k this is a shift of half a fine pixel (ICBI's output taken as is would be shifted
// by a quarter of an input pixel at ×2: 4.1 dB lower on the photos under a Lanczos3 downscale,
// 2 to 8 dB per image, in the prototype); at ×2.5 the same pass shrinks
// the ×4 grid by 1.6 (in the prototype 0.04 dB above one step and a ×1.25 enlargement).
// Catmull-Rom reproduces a ramp exactly and scored above Lanczos3 and a cubic spline for this
// pass in the prototype (Lanczos3's gain above 1 near the input's Nyquist frequency lifts the
// steps' staircase).
// The bench measures the shift on a ramp (ramp_alignment.h), so it checks the convention.
#pragma once

#include <cstdint>

#include "image.h"

namespace bench {

// `input` (any channel count, values in [0, 1]) magnified to width × height (each at least the
// input's side) by ICBI ×2 steps and a final Catmull-Rom pass, in float.
ddt::Image magnifyWithIcbi(const ddt::Image& input, uint32_t width, uint32_t height);

}  // namespace bench
