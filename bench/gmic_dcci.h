// G'MIC's DCCI (directional cubic convolution interpolation, Zhou, Shen & Zhang 2012), a ×2
// peer, run as the `gmic` command line on PNG files in a temporary folder:
//   gmic in.png dcci2x cut 0,255 o out.png
// The column is "n/a" with the reason when `gmic` is missing or has no `dcci2x` (Debian 12's
// G'MIC 2.9.4 has none). DCCI keeps every input pixel as output pixel (2x, 2y), i.e. samples
// input coordinate X / 2, not ddtup's (X + 0.5) / 2 − 0.5: dcciMisalignment() measures it on a
// ramp, and the report states it beside the scores rather than resampling (which would blur).
#pragma once

#include <string>

#include "image.h"

namespace bench {

// "" when `gmic … dcci2x` runs here, else why not.
std::string dcciUnavailableReason();

// `input` (grey or RGB, 8-bit values) magnified ×2 by DCCI; 8-bit values.
ddt::Image magnifyWithDcci(const ddt::Image& input);

// The mean (sampled − expected) input coordinate, in input pixels, of a horizontal ramp
// magnified by DCCI, against ddtup's convention (away from the borders).
double dcciMisalignment();

}  // namespace bench
