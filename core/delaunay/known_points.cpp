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

// The corners of the convex hull of `places` (row-major): Andrew's monotone chain, along y
// here, without the points on its sides.
std::vector<Position> convexHullOf(const std::vector<Position>& places) {
    std::vector<Position> hull;
    auto chain = [&](auto first, auto last) {
        const size_t base = hull.size();
        for (auto it = first; it != last; ++it) {
            while (hull.size() >= base + 2 && orient(hull[hull.size() - 2], hull.back(), *it) <= 0) hull.pop_back();
            hull.push_back(*it);
        }
        hull.pop_back();  // the other chain's first point
    };
    chain(places.begin(), places.end());
    chain(places.rbegin(), places.rend());
    return hull;
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
    hull_ = convexHullOf(places);
    const uint32_t c = values.channels;
    places_.resize(places.size());
    values_ = values;
    for (size_t i = 0; i < places.size(); ++i) {
        const uint32_t to = next[blockOf(places[i])]++;
        places_[to] = places[i];
        std::copy_n(values.pixels.data() + i * c, c, values_.pixels.data() + size_t(to) * c);
    }
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

SampleSet KnownPoints::samplesIn(const PackedImage&, const PixelRect& rect) const {
    std::vector<uint32_t> ids;
    forEachIn(rect, [&](uint32_t i) { ids.push_back(i); });
    // Row-major, as the triangulation takes them: the blocks' runs interleave within a block row.
    std::sort(ids.begin(), ids.end(), [&](uint32_t a, uint32_t b) {
        const Position &p = places_[a], &q = places_[b];
        return p.y != q.y ? p.y < q.y : p.x < q.x;
    });
    SampleSet set;
    const int32_t dx = int32_t(rect.x0) * kPositionOne, dy = int32_t(rect.y0) * kPositionOne;
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

template <typename Visit>
void KnownPoints::forEachNear(long double cx, long double cy, long double radius, Visit visit) const {
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
        for (uint32_t i = first; i < end; ++i) visit(i);
    }
}

PixelRect KnownPoints::cropHolding(const Mesh& mesh, const PixelRect& crop, const PixelRect& rect) const {
    const int32_t dx = int32_t(crop.x0) * kPositionOne, dy = int32_t(crop.y0) * kPositionOne;
    auto at = [&](uint32_t v) { return Position{mesh.positions[v].x + dx, mesh.positions[v].y + dy}; };
    const int32_t rx0 = int32_t(rect.x0) * kPositionOne, rx1 = int32_t(rect.x1 - 1) * kPositionOne;
    const int32_t ry0 = int32_t(rect.y0) * kPositionOne, ry1 = int32_t(rect.y1 - 1) * kPositionOne;
    // Whether the box of the positions meets rect's pixel centres' rectangle.
    auto near = [&](std::initializer_list<Position> ps) {
        int32_t x0 = INT32_MAX, x1 = INT32_MIN, y0 = INT32_MAX, y1 = INT32_MIN;
        for (const Position& p : ps) x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
        return x1 >= rx0 && x0 <= rx1 && y1 >= ry0 && y0 <= ry1;
    };
    const int32_t cx0 = dx, cx1 = int32_t(crop.x1 - 1) * kPositionOne;
    const int32_t cy0 = dy, cy1 = int32_t(crop.y1 - 1) * kPositionOne;
    auto inCrop = [&](const Position& p) { return p.x >= cx0 && p.x <= cx1 && p.y >= cy0 && p.y <= cy1; };
    PixelRect grown = crop;
    auto hold = [&](const Position& p) {
        grown.x0 = std::min(grown.x0, uint32_t(p.x / kPositionOne));
        grown.y0 = std::min(grown.y0, uint32_t(p.y / kPositionOne));
        grown.x1 = std::max(grown.x1, uint32_t((p.x + kPositionOne - 1) / kPositionOne) + 1);
        grown.y1 = std::max(grown.y1, uint32_t((p.y + kPositionOne - 1) / kPositionOne) + 1);
    };
    forEachTriangle(mesh, [&](const Triangle& t) {
        Position a = at(t.v0), b = at(t.v1), c = at(t.v2);
        if (!near({a, b, c})) return;
        if (orient(a, b, c) < 0) std::swap(b, c);
        // The circumcircle, roughly (long double); the exact test decides for each point near it.
        const long double bx = b.x - a.x, by = b.y - a.y, qx = c.x - a.x, qy = c.y - a.y;
        const long double d = 2.0L * (bx * qy - by * qx);
        const long double b2 = bx * bx + by * by, q2 = qx * qx + qy * qy;
        const long double ux = (qy * b2 - by * q2) / d, uy = (bx * q2 - qx * b2) / d;
        forEachNear(a.x + ux, a.y + uy, std::sqrt(ux * ux + uy * uy), [&](uint32_t i) {
            const Position& p = places_[i];
            if (!inCrop(p) && inCircle(a, b, c, p)) hold(p);
        });
    });
    for (const EdgeVertices& edge : mesh.vertices) {
        if (edge.l != kNone && edge.r != kNone) continue;
        const Position a = at(edge.a), b = at(edge.b);
        if (!near({a, b})) continue;
        // The edge's triangle is left of a→b when it is l: the outside is right of it.
        for (const Position& corner : hull_) {
            const int64_t side = orient(a, b, corner);
            if (edge.l != kNone ? side < 0 : side > 0) hold(corner);
        }
    }
    return grown;
}

void KnownPoints::measureHoles() {
    const uint32_t side = cell();
    const uint32_t w = (width() + side - 1) / side, h = (height() + side - 1) / side;
    std::vector<uint8_t> marked(size_t(w) * h, 0);
    for (const Position& p : places_) marked[size_t(nearestPixel(p.y) / side) * w + nearestPixel(p.x) / side] = 1;
    measureFrom(marked);
}

}  // namespace ddt
