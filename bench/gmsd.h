// GMSD, gradient magnitude similarity deviation (Xue, Zhang, Mou & Bovik, IEEE TIP 2014):
// how unevenly the local gradient structure of a reconstruction matches the original's.
// Lower is better; 0 for identical images. As the authors' reference code computes it:
// - on luma Y = 0.299 R + 0.587 G + 0.114 B of the 8-bit values (core/metrics.h's luma,
//   grey: the value), in levels 0..255;
// - both images filtered with the 2 × 2 average and downsampled by 2: value (i, j) is the mean
//   of Y at (2i..2i+1, 2j..2j+1), zero beyond the image (MATLAB conv2 'same', then every
//   second row and column from the first); ⌈w/2⌉ × ⌈h/2⌉ values;
// - Prewitt gradients, the 3 × 3 kernels [1 0 −1; 1 0 −1; 1 0 −1] / 3 and its transpose, with
//   zero padding; m = √(gx² + gy²);
// - GMS = (2 m_x m_y + c) / (m_x² + m_y² + c) per position, c = 170;
// - GMSD = the standard deviation of the GMS map (normalised by n − 1, as MATLAB's std2).
#pragma once

#include "metrics.h"

namespace bench {

// Both images must have the same size and channel count, at least 2 × 2 pixels.
double gradientMagnitudeSimilarityDeviation(const ddt::ByteImage& original, const ddt::ByteImage& other);

}  // namespace bench
