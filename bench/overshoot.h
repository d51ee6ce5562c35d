// Overshoot: how far a magnified image leaves the range of the input values around each of
// its pixels, i.e. the ringing and halos an interpolator adds (lower is better; a method that
// stays in the local input range scores 0).
// - Output pixel X samples the input at p = (X + 0.5) / sx − 0.5 input pixels (sx = output /
//   input width; likewise Y with sy), the convention of ddtup's renderer.
// - Its neighbourhood: the 4 × 4 input pixels nearest p, floor(p) − 1 … floor(p) + 2 per axis
//   (primary), or the 2 × 2 around p, floor(p) … floor(p) + 1; indices clamped to the image.
// - Per output pixel and colour channel, on 8-bit levels (core/metrics.h's 8-bit values):
//   overshoot = max(0, v − max, min − v) over the neighbourhood's values of that channel.
// - Reported: the mean overshoot over all output values (levels), and the share of values
//   whose overshoot exceeds 4 levels.
#pragma once

#include "metrics.h"

namespace bench {

struct OvershootScores {
    double mean_levels = 0.0;
    double share_over_4 = 0.0;  // fraction; tables show percent
};

struct Overshoot {
    OvershootScores nearest_4x4;  // primary
    OvershootScores nearest_2x2;
};

// `output` magnifies `input` (same channel count).
Overshoot measureOvershoot(const ddt::ByteImage& input, const ddt::ByteImage& output);

}  // namespace bench
