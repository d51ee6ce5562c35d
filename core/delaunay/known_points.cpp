#include "known_points.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

#include "predicates.h"

namespace ddt {

namespace {

// Points are looked up by blocks of this many pixels a side.
constexpr uint32_t kPointBlock = 32;
// The distance grid's cells at most per point (5 bytes a cell while measuring: 20 bytes a point).
constexpr uint64_t kCellsPerPoint = 4;

// The pixel whose centre is nearest `place` (ties up), along one axis.
uint32_t nearestPixel(int32_t place) { return uint32_t((place + kPositionOne / 2) / kPositionOne); }

uint32_t cellFor(uint32_t width, uint32_t height, size_t points) {
    uint32_t cell = 1;
    auto cells = [&](uint32_t side) { return uint64_t((width + side - 1) / side) * ((height + side - 1) / side); };
    while (cell < 32 && cells(cell) > kCellsPerPoint * points) cell *= 2;
    return cell;
}

}  // namespace

KnownPoints::KnownPoints(uint32_t width, uint32_t height, const std::vector<Position>& places, const Image& values)
    : KnownSamples(width, height, cellFor(width, height, places.size()),
                   // A cell's diagonal, √2 · cell, a little over for the float rounding.
                   1.41422f * float(cellFor(width, height, places.size()))) {
    assert(values.width == places.size() && values.height == 1);
    block_columns_ = (width + kPointBlock - 1) / kPointBlock;
    const uint32_t block_rows = (height + kPointBlock - 1) / kPointBlock;
    auto blockOf = [&](const Position& p) {
        return size_t(nearestPixel(p.y) / kPointBlock) * block_columns_ + nearestPixel(p.x) / kPointBlock;
    };
    // A counting sort by block keeps the row-major order within each block.
    block_first_.assign(size_t(block_columns_) * block_rows + 1, 0);
    for (const Position& p : places) ++block_first_[blockOf(p) + 1];
    std::partial_sum(block_first_.begin(), block_first_.end(), block_first_.begin());
    std::vector<uint32_t> next(block_first_.begin(), block_first_.end() - 1);
    const uint32_t c = values.channels;
    places_.resize(places.size());
    values_ = values;
    std::vector<uint32_t> moved_to(places.size());
    for (size_t i = 0; i < places.size(); ++i) {
        const uint32_t to = next[blockOf(places[i])]++;
        moved_to[i] = to;
        places_[to] = places[i];
        std::copy_n(values.pixels.data() + i * c, c, values_.pixels.data() + size_t(to) * c);
    }
    std::vector<uint32_t> hull = convexHullOf(places);
    for (uint32_t& i : hull) i = moved_to[i];
    keepHullCorners(std::move(hull));
}

uint64_t KnownPoints::bytesPerPoint(uint32_t channels) {
    return sizeof(Position) + sizeof(float) * channels + kCellsPerPoint * 5;
}

template <typename Visit>
void KnownPoints::forEachIn(const PixelRect& rect, Visit visit) const {
    // A point belongs to the rect when it lies in its pixel centres' rectangle.
    const int32_t x0 = int32_t(rect.x0) * kPositionOne, x1 = int32_t(rect.x1 - 1) * kPositionOne;
    const int32_t y0 = int32_t(rect.y0) * kPositionOne, y1 = int32_t(rect.y1 - 1) * kPositionOne;
    for (uint32_t by = rect.y0 / kPointBlock; by <= (rect.y1 - 1) / kPointBlock; ++by) {
        const size_t row = size_t(by) * block_columns_;
        const uint32_t first = block_first_[row + rect.x0 / kPointBlock];
        const uint32_t end = block_first_[row + (rect.x1 - 1) / kPointBlock + 1];
        for (uint32_t i = first; i < end; ++i) {
            const Position& p = places_[i];
            if (p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1) visit(i);
        }
    }
}

std::string KnownPoints::problemIn(const PixelRect& rect) const {
    // The first two points fix a line; any third off it makes a triangle (the points are distinct).
    Position p{}, q{};
    uint64_t count = 0;
    bool triangle = false;
    forEachIn(rect, [&](uint32_t i) {
        const Position& r = places_[i];
        if (count == 0) p = r;
        else if (count == 1) q = r;
        else if (int64_t(q.x - p.x) * (r.y - p.y) != int64_t(q.y - p.y) * (r.x - p.x)) triangle = true;
        ++count;
    });
    if (triangle) return "";
    return count < 3 ? "fewer than 3 points" : "all points are collinear";
}

std::vector<uint32_t> KnownPoints::samplesAlongBorder(const PixelRect& rect) const {
    const uint32_t w = width(), h = height();
    // The bands of the sides rect touches, each a block deep first, then as deep as the rule
    // asks for that block-deep band.
    std::vector<PixelRect> bands;
    auto addBand = [&](auto bandOf) {
        const PixelRect first = bandOf(std::min(std::max(w, h), 32u));
        bands.push_back(bandOf(growthFor(first)));
    };
    if (rect.x0 == 0) addBand([&](uint32_t d) { return PixelRect{0, 0, std::min(w, d), h}; });
    if (rect.y0 == 0) addBand([&](uint32_t d) { return PixelRect{0, 0, w, std::min(h, d)}; });
    if (rect.x1 == w) addBand([&](uint32_t d) { return PixelRect{w - std::min(w, d), 0, w, h}; });
    if (rect.y1 == h) addBand([&](uint32_t d) { return PixelRect{0, h - std::min(h, d), w, h}; });
    const int32_t rx0 = int32_t(rect.x0) * kPositionOne, rx1 = int32_t(rect.x1 - 1) * kPositionOne;
    const int32_t ry0 = int32_t(rect.y0) * kPositionOne, ry1 = int32_t(rect.y1 - 1) * kPositionOne;
    std::vector<uint32_t> ids;
    for (const PixelRect& band : bands)
        forEachIn(band, [&](uint32_t i) {
            const Position& p = places_[i];
            if (!(p.x >= rx0 && p.x <= rx1 && p.y >= ry0 && p.y <= ry1)) ids.push_back(i);
        });
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    return ids;
}

SampleSet KnownPoints::samplesIn(const PackedImage&, const PixelRect& rect, const std::vector<uint32_t>& extra) const {
    std::vector<uint32_t> ids = extra;  // outside rect: samplesBreaking finds only those
    forEachIn(rect, [&](uint32_t i) { ids.push_back(i); });
    // Row-major, as the triangulation takes them: the blocks' runs interleave within a block row.
    std::sort(ids.begin(), ids.end(), [&](uint32_t a, uint32_t b) {
        const Position &p = places_[a], &q = places_[b];
        return p.y != q.y ? p.y < q.y : p.x < q.x;
    });
    const PixelRect bounds = boundsOf(rect, extra);
    SampleSet set;
    const int32_t dx = int32_t(bounds.x0) * kPositionOne, dy = int32_t(bounds.y0) * kPositionOne;
    set.places.resize(ids.size());
    Image& values = set.values;
    values.width = uint32_t(ids.size());
    values.height = 1;
    values.channels = values_.channels;
    values.sample_type = values_.sample_type;
    values.metadata = values_.metadata;
    values.pixels.resize(ids.size() * values.channels);
    for (size_t k = 0; k < ids.size(); ++k) {
        set.places[k] = {places_[ids[k]].x - dx, places_[ids[k]].y - dy};
        std::copy_n(values_.pixels.data() + size_t(ids[k]) * values.channels, values.channels,
                    values.pixels.data() + k * values.channels);
    }
    return set;
}

void KnownPoints::addSamplesNear(long double cx, long double cy, long double radius, const PixelRect&,
                                 std::vector<uint32_t>& ids) const {
    const long double one = kPositionOne, band = kPointBlock * one;
    const uint32_t block_rows = uint32_t(block_first_.size() - 1) / block_columns_;
    // A point's block is its nearest pixel's: it lies up to half a pixel outside the block's
    // pixel centres; one pixel of margin more covers the rounding of the circle.
    const long double margin = 1.5L * one;
    const long double top = std::max(0.0L, std::floor((cy - radius - margin) / band));
    for (uint32_t by = uint32_t(std::min<long double>(top, block_rows)); by < block_rows; ++by) {
        const long double y0 = by * band - margin, y1 = (by + 1) * band + margin;
        if (y0 > cy + radius) break;
        const long double dy = cy < y0 ? y0 - cy : cy > y1 ? cy - y1 : 0.0L;
        if (dy > radius) continue;
        const long double half = std::sqrt(radius * radius - dy * dy) + margin;
        const long double left = std::floor((cx - half) / band), right = std::floor((cx + half) / band);
        if (right < 0 || left >= block_columns_) continue;
        const size_t row = size_t(by) * block_columns_;
        const uint32_t first = block_first_[row + uint32_t(std::max(0.0L, left))];
        const uint32_t end = block_first_[row + uint32_t(std::min<long double>(right, block_columns_ - 1)) + 1];
        for (uint32_t i = first; i < end; ++i) ids.push_back(i);
    }
}

void KnownPoints::measureHoles() {
    const uint32_t side = cell();
    const uint32_t w = (width() + side - 1) / side, h = (height() + side - 1) / side;
    std::vector<uint8_t> marked(size_t(w) * h, 0);
    for (const Position& p : places_) marked[size_t(nearestPixel(p.y) / side) * w + nearestPixel(p.x) / side] = 1;
    measureFrom(marked);
}

}  // namespace ddt
