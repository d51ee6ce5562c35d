// The camera-like protocol: optics and the pixel's aperture as one Gaussian of σ = 0.4·f
// original pixels, sampled at each low-resolution pixel's centre, then sensor noise of
// σ = 1/255 (a fixed seed, so every run sees the same noise). The blur is computed in double,
// separably, with the samples past the border taken from the nearest one; the result is
// returned unrounded.
#pragma once

#include "image.h"
#include "magnification.h"

namespace bench {

// `original`'s sides must be multiples of factor.numerator.
ddt::Image cameraCapture(const ddt::Image& original, Magnification factor);

}  // namespace bench
