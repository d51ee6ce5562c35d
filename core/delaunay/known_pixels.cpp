#include "known_pixels.h"

#include <algorithm>
#include <cmath>

namespace ddt {

KnownPixels::KnownPixels(uint32_t width, uint32_t height, std::vector<uint8_t> known)
    : KnownSamples(width, height, 1, 1.0f), known_(std::move(known)) {}

std::vector<uint32_t> KnownPixels::idsIn(const PixelRect& rect) const { return idsIn(rect, rect); }

std::vector<uint32_t> KnownPixels::idsIn(const PixelRect& rect, const PixelRect& grid) const {
    std::vector<uint32_t> ids;
    for (uint32_t y = rect.y0; y < rect.y1; ++y)
        for (uint32_t x = rect.x0; x < rect.x1; ++x)
            if (known(x, y)) ids.push_back((y - grid.y0) * grid.width() + (x - grid.x0));
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

SampleSet KnownPixels::samplesIn(const PackedImage& input, const PixelRect& rect, const std::vector<uint32_t>& extra) const {
    const PixelRect bounds = boundsOf(rect, extra);
    const std::vector<uint32_t> inside = idsIn(rect, bounds);
    std::vector<uint32_t> far;
    far.reserve(extra.size());
    for (uint32_t id : extra) far.push_back((id / width() - bounds.y0) * bounds.width() + (id % width() - bounds.x0));
    // Both ascend: the frame's row-major order is the bounds' too.
    std::vector<uint32_t> ids(inside.size() + far.size());
    std::merge(inside.begin(), inside.end(), far.begin(), far.end(), ids.begin());
    return {input.crop(bounds), std::move(ids), {}};
}

void KnownPixels::measureHoles() {
    measureFrom(known_);
    // The hull's corners are among each row's first and last known pixels.
    std::vector<uint32_t> ids;
    for (uint32_t y = 0; y < height(); ++y) {
        const uint8_t* row = known_.data() + size_t(y) * width();
        uint32_t x0 = 0, x1 = width();
        while (x0 < width() && row[x0] == 0) ++x0;
        if (x0 == width()) continue;
        while (row[--x1] == 0) {}
        ids.push_back(y * width() + x0);
        if (x1 != x0) ids.push_back(y * width() + x1);
    }
    std::vector<Position> ends(ids.size());
    std::transform(ids.begin(), ids.end(), ends.begin(), [&](uint32_t id) { return placeOf(id); });
    std::vector<uint32_t> corners = convexHullOf(ends);
    for (uint32_t& i : corners) i = ids[i];
    keepHullCorners(std::move(corners));
}

void KnownPixels::addSamplesNear(long double cx, long double cy, long double radius, const PixelRect& rect,
                                 std::vector<uint32_t>& ids) const {
    // In pixels, the disk grown by a pixel: the exact test decides, the margin covers the rounding.
    const long double one = kPositionOne, x = cx / one, y = cy / one, r = radius / one + 1.0L;
    const long double top = std::max(0.0L, std::ceil(y - r)), bottom = std::min<long double>(height() - 1, std::floor(y + r));
    if (top > bottom) return;
    auto addRun = [&](uint32_t py, uint32_t x0, uint32_t x1) {  // x0 … x1 − 1
        for (uint32_t px = x0; px < x1; ++px)
            if (known(px, py)) ids.push_back(py * width() + px);
    };
    for (uint32_t py = uint32_t(top); py <= uint32_t(bottom); ++py) {
        const long double dy = py - y, half = std::sqrt(std::max(0.0L, r * r - dy * dy));
        const long double left = std::max(0.0L, std::ceil(x - half));
        const long double right = std::min<long double>(width() - 1, std::floor(x + half));
        if (left > right) continue;
        const uint32_t x0 = uint32_t(left), x1 = uint32_t(right) + 1;
        if (py < rect.y0 || py >= rect.y1) {
            addRun(py, x0, x1);
        } else {  // rect's pixels are the crop's already
            addRun(py, x0, std::min(x1, rect.x0));
            addRun(py, std::max(x0, rect.x1), x1);
        }
    }
}

}  // namespace ddt
