// How far a grey output is from a plane: the check of the command-line tests that rebuild a
// linear field from samples (test_cli_mask.cpp, test_cli_points.cpp).
#pragma once

#include <algorithm>
#include <cmath>

#include "image.h"

namespace ddt::test {

// The largest |output − plane| over the pixels of `out`, a grey image of a width × height
// frame magnified: output pixel X samples input x = (X + 0.5) · width / out.width − 0.5,
// clamped into the frame (core/image/render.h), and y alike.
template <typename Plane>
double worstPlaneError(const Image& out, uint32_t width, uint32_t height, Plane plane) {
    double worst = 0.0;
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x) {
            const double sx = std::clamp((x + 0.5) * width / out.width - 0.5, 0.0, double(width - 1));
            const double sy = std::clamp((y + 0.5) * height / out.height - 0.5, 0.0, double(height - 1));
            worst = std::max(worst, std::abs(out.pixels[size_t(y) * out.width + x] - plane(sx, sy)));
        }
    return worst;
}

}  // namespace ddt::test
