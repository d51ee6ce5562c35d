#include "known_pixels.h"

namespace ddt {

KnownPixels::KnownPixels(uint32_t width, uint32_t height, std::vector<uint8_t> known)
    : KnownSamples(width, height, 1, 1.0f), known_(std::move(known)) {}

std::vector<uint32_t> KnownPixels::idsIn(const PixelRect& rect) const {
    std::vector<uint32_t> ids;
    for (uint32_t y = rect.y0; y < rect.y1; ++y)
        for (uint32_t x = rect.x0; x < rect.x1; ++x)
            if (known(x, y)) ids.push_back((y - rect.y0) * rect.width() + (x - rect.x0));
    return ids;
}

std::string KnownPixels::problemIn(const PixelRect& rect) const {
    // The first two known pixels fix a line; any third off it makes a triangle.
    int64_t px = 0, py = 0, qx = 0, qy = 0;
    uint64_t count = 0;
    for (uint32_t y = rect.y0; y < rect.y1; ++y)
        for (uint32_t x = rect.x0; x < rect.x1; ++x) {
            if (!known(x, y)) continue;
            if (count == 0) px = x, py = y;
            else if (count == 1) qx = x, qy = y;
            else if ((qx - px) * (int64_t(y) - py) != (qy - py) * (int64_t(x) - px)) return "";
            ++count;
        }
    return count < 3 ? "fewer than 3 points" : "all points are collinear";
}

SampleSet KnownPixels::samplesIn(const PackedImage& input, const PixelRect& rect, const std::vector<uint32_t>&) const {
    return {input.crop(rect), idsIn(rect), {}};
}

}  // namespace ddt
