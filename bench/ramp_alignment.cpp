#include "ramp_alignment.h"

#include <algorithm>
#include <cmath>

namespace bench {

namespace {

// A side × side grey image whose value is its x (or y) coordinate.
ddt::Image ramp(uint32_t side, bool along_x) {
    ddt::Image image;
    image.width = image.height = side;
    image.channels = 1;
    image.pixels.resize(size_t(side) * side);
    for (uint32_t y = 0; y < side; ++y)
        for (uint32_t x = 0; x < side; ++x) image.pixels[size_t(y) * side + x] = float(along_x ? x : y);
    return image;
}

}  // namespace

double rampMisalignment(const Magnifier& magnify, std::initializer_list<double> scales) {
    const uint32_t side = 32, margin = 4;  // input pixels kept away from the borders
    double worst = 0.0;
    for (double scale : scales)
        for (bool along_x : {true, false}) {
            const uint32_t out_side = uint32_t(side * scale);
            const ddt::Image out = magnify(ramp(side, along_x), out_side, out_side);
            for (uint32_t y = 0; y < out_side; ++y)
                for (uint32_t x = 0; x < out_side; ++x) {
                    const double expected = ((along_x ? x : y) + 0.5) / scale - 0.5;
                    if (expected < margin || expected > side - 1 - margin) continue;
                    worst = std::max(worst, std::fabs(out.pixels[size_t(y) * out_side + x] - expected));
                }
        }
    return worst;
}

}  // namespace bench
