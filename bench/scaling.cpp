#include "scaling.h"

#include <cmath>

#include "memory_png.h"
#include "protocol.h"

namespace bench {

namespace {

const uint32_t kSmallestSide = 64;

}  // namespace

std::vector<uint32_t> scalingSides(uint32_t max_side) {
    std::vector<uint32_t> sides;
    for (int half_octave = 0;; ++half_octave) {
        const uint32_t side = uint32_t(std::lround(kSmallestSide * std::pow(2.0, half_octave / 2.0)));
        if (side > max_side) break;
        sides.push_back(side);
    }
    return sides;
}

ddt::Image resizedSquare(const ddt::Image& image, uint32_t side) {
    if (image.width == side && image.height == side) return roundedTo8Bit(image);
    // "" lets OIIO pick its default: lanczos3 when shrinking, blackman-harris when growing.
    return roundedTo8Bit(resizeWithFilter(image, "", side, side));
}

std::vector<ScalingResult> measureScaling(const std::vector<DdtMethod>& methods, const std::string& dataset,
                                          const std::string& image_name, const ddt::Image& input, uint32_t warmups,
                                          uint32_t repeats) {
    const PngInMemory png = encodePng(input);
    const ddt::OutputSize out{input.width * kScalingFactor, input.height * kScalingFactor};
    std::vector<ScalingResult> results;
    for (const DdtMethod& method : methods) {
        if (!method.unavailable.empty()) continue;
        results.push_back({dataset, image_name, input.width, input.height, method.key,
                           measureDdt(method, png, out, warmups, repeats, nullptr)});
    }
    return results;
}

}  // namespace bench
