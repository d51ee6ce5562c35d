// The evaluation protocol of the paper's Sec. 6: every original is cropped to a multiple of
// the factor, halved with bilinear filtering until it is 1/factor of its size, magnified
// back by each method, and compared with the original.
//
// Halving uses OIIO's "triangle" filter at its default width, which OIIO scales to the
// source pixels when shrinking (a tent over 4 source pixels per halving). The halvings run
// in float and the result is rounded to 8 bits once, as a stored low-resolution image would
// be; rounding after every halving instead moves PSNR by about 0.005 dB.
#pragma once

#include <cstdint>
#include <string>

#include "image.h"

namespace bench {

// The original as the bench compares with it: grey or RGB. An alpha channel is dropped
// (its colour stays premultiplied, i.e. over black) and reported in `note`.
ddt::Image loadOriginal(const std::string& path, std::string& note);

// The centred width × height part of `image`.
ddt::Image cropCentred(const ddt::Image& image, uint32_t width, uint32_t height);

// `image` cropped (centred) to the largest size whose sides are multiples of `factor`.
ddt::Image cropToMultiple(const ddt::Image& image, uint32_t factor);

// The low-resolution input for a power-of-two `factor`: log2(factor) halvings in float,
// then rounded to 8 bits.
ddt::Image makeLowRes(const ddt::Image& original, uint32_t factor);

// `image` resized to width × height by the named OIIO filter at its default width, in float
// (values may leave [0, 1] for filters with negative lobes; the metrics clamp).
ddt::Image resizeWithFilter(const ddt::Image& image, const std::string& filter, uint32_t width, uint32_t height);

// Every value rounded to the nearest k / 255, clamped to [0, 1].
ddt::Image roundedTo8Bit(const ddt::Image& image);

}  // namespace bench
