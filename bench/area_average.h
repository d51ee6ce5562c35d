// Exact area averaging (protocol B): each low-resolution pixel is the mean of the original
// over its footprint, a square of factor × factor original pixels. For a fractional factor
// (×2.5) the footprint's edges cut through original pixels, which count with the fraction of
// their area it covers. Computed in double, separably (a box's area is the product of its
// extents per axis), and returned unrounded.
#pragma once

#include "image.h"
#include "magnification.h"

namespace bench {

// `original`'s sides must be multiples of factor.numerator.
ddt::Image areaAverage(const ddt::Image& original, Magnification factor);

}  // namespace bench
