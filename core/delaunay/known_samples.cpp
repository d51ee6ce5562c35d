#include "known_samples.h"

#include <algorithm>
#include <cmath>

#include "parallel.h"
#include "predicates.h"

namespace ddt {

namespace {

// Distances are kept per block of this side, in pixels: a crop's rule reads them over its
// rectangle, and a block's maximum bounds each of its cells' from above.
constexpr uint32_t kBlock = 32;
constexpr uint32_t kFar = UINT32_MAX;  // no sample in the column

// Per cell of a w × h grid, the distance in rows to the nearest marked cell of its column
// (kFar if none).
std::vector<uint32_t> columnDistances(const std::vector<uint8_t>& marked, uint32_t w, uint32_t h) {
    std::vector<uint32_t> distance(size_t(w) * h, kFar);
    parallelFor(w, 64, [&](size_t begin, size_t end) {
        for (uint32_t x = uint32_t(begin); x < end; ++x) {
            uint32_t last = kFar;
            for (uint32_t y = 0; y < h; ++y) {
                if (marked[size_t(y) * w + x]) last = y;
                if (last != kFar) distance[size_t(y) * w + x] = y - last;
            }
            last = kFar;
            for (uint32_t y = h; y-- > 0;) {
                if (marked[size_t(y) * w + x]) last = y;
                uint32_t& d = distance[size_t(y) * w + x];
                if (last != kFar) d = std::min(d, last - y);
            }
        }
    });
    return distance;
}

// A triangle's circumcircle, fixed point, roughly: the exact in-circle test decides for each
// sample near it. Long doubles: the centre's terms are at most |b| / |b − c| < 2^27 times the
// radius (differences below 2^27, predicates.h), so its error stays far below a pixel.
struct Circle {
    long double x, y, radius;

    // Whether it lies a pixel (the rounding's margin) or more inside [x0, x1] × [y0, y1].
    bool inside(int32_t x0, int32_t y0, int32_t x1, int32_t y1) const {
        const long double r = radius + kPositionOne;
        return x - r >= x0 && x + r <= x1 && y - r >= y0 && y + r <= y1;
    }
};

Circle circumcircleOf(Position a, Position b, Position c) {
    const long double bx = b.x - a.x, by = b.y - a.y, qx = c.x - a.x, qy = c.y - a.y;
    const long double d = 2.0L * (bx * qy - by * qx);
    const long double b2 = bx * bx + by * by, q2 = qx * qx + qy * qy;
    const long double ux = (qy * b2 - by * q2) / d, uy = (bx * q2 - qx * b2) / d;
    return {a.x + ux, a.y + uy, std::sqrt(ux * ux + uy * uy)};
}

}  // namespace

void KnownSamples::measureFrom(const std::vector<uint8_t>& marked) {
    const uint32_t w = (width_ + cell_ - 1) / cell_, h = (height_ + cell_ - 1) / cell_;
    const uint32_t cells_a_block = kBlock / cell_;
    const std::vector<uint32_t> column = columnDistances(marked, w, h);
    block_columns_ = (width_ + kBlock - 1) / kBlock;
    const uint32_t block_rows = (height_ + kBlock - 1) / kBlock;
    block_distance_.assign(size_t(block_columns_) * block_rows, 0.0f);
    // Row by row, d²(x) = min over columns q of (x − q)² + column(q)²: the lower envelope of
    // those parabolas (Felzenszwalb and Huttenlocher, "Distance Transforms of Sampled
    // Functions", 2012), in exact integers. A block row belongs to one task: no races.
    parallelFor(block_rows, 1, [&](size_t begin, size_t end) {
        std::vector<uint32_t> parabolas(w);
        for (uint32_t y = uint32_t(begin) * cells_a_block; y < std::min<size_t>(h, end * cells_a_block); ++y) {
            const uint32_t* rows = column.data() + size_t(y) * w;
            auto lift = [&](uint32_t q) { return int64_t(rows[q]) * rows[q] + int64_t(q) * q; };
            // r overtakes q no later than q overtakes p: q never lowest (as nearest_fill.cpp).
            auto hidden = [&](uint32_t p, uint32_t q, uint32_t r) {
                return (lift(r) - lift(q)) * int64_t(q - p) <= (lift(q) - lift(p)) * int64_t(r - q);
            };
            size_t count = 0;
            for (uint32_t q = 0; q < w; ++q) {
                if (rows[q] == kFar) continue;
                while (count >= 2 && hidden(parabolas[count - 2], parabolas[count - 1], q)) --count;
                parabolas[count++] = q;
            }
            float* blocks = block_distance_.data() + size_t(y / cells_a_block) * block_columns_;
            if (count == 0) {  // no sample at all: as far as the frame is wide and tall
                const float far = std::hypot(float(width_), float(height_));
                for (uint32_t b = 0; b < block_columns_; ++b) blocks[b] = far;
                continue;
            }
            size_t k = 0;
            for (uint32_t x = 0; x < w; ++x) {
                auto at = [&](uint32_t q) {
                    const int64_t dx = int64_t(x) - q;
                    return dx * dx + int64_t(rows[q]) * rows[q];
                };
                while (k + 1 < count && at(parabolas[k + 1]) <= at(parabolas[k])) ++k;
                float& block = blocks[x / cells_a_block];
                block = std::max(block, float(cell_) * std::sqrt(float(at(parabolas[k]))));
            }
        }
    });
}

float KnownSamples::largestDistanceIn(const PixelRect& rect) const {
    float largest = 0.0f;
    for (uint32_t by = rect.y0 / kBlock; by <= (rect.y1 - 1) / kBlock; ++by)
        for (uint32_t bx = rect.x0 / kBlock; bx <= (rect.x1 - 1) / kBlock; ++bx)
            largest = std::max(largest, block_distance_[size_t(by) * block_columns_ + bx]);
    return largest;
}

uint32_t KnownSamples::growthFor(const PixelRect& rect) const {
    return uint32_t(std::ceil(2.0f * (largestDistanceIn(rect) + spread_))) + 1;
}

PixelRect KnownSamples::cropFor(const PixelRect& rect, uint32_t max_growth) const {
    auto grown = [&](uint32_t g) {
        return PixelRect{rect.x0 - std::min(rect.x0, g), rect.y0 - std::min(rect.y0, g),
                         uint32_t(std::min<uint64_t>(width_, uint64_t(rect.x1) + g)),
                         uint32_t(std::min<uint64_t>(height_, uint64_t(rect.y1) + g))};
    };
    const PixelRect whole{0, 0, width_, height_};
    uint32_t g = 0;
    for (;;) {
        const PixelRect crop = grown(g);
        const bool everything = crop.x0 == 0 && crop.y0 == 0 && crop.x1 == width_ && crop.y1 == height_;
        if (everything) return whole;
        const uint32_t needed = growthFor(crop);
        if (needed <= g || g == max_growth) return problemIn(crop).empty() ? crop : whole;
        g = std::min(needed, max_growth);
    }
}

std::vector<uint32_t> KnownSamples::samplesAlongBorder(const PixelRect&) const { return {}; }

PixelRect KnownSamples::boundsOf(const PixelRect& rect, const std::vector<uint32_t>& extra) const {
    PixelRect bounds = rect;
    for (uint32_t i : extra) {
        const Position p = placeOf(i);
        bounds.x0 = std::min(bounds.x0, uint32_t(p.x / kPositionOne));
        bounds.y0 = std::min(bounds.y0, uint32_t(p.y / kPositionOne));
        bounds.x1 = std::max(bounds.x1, uint32_t((p.x + kPositionOne - 1) / kPositionOne) + 1);
        bounds.y1 = std::max(bounds.y1, uint32_t((p.y + kPositionOne - 1) / kPositionOne) + 1);
    }
    return bounds;
}

std::vector<uint32_t> KnownSamples::convexHullOf(const std::vector<Position>& places) {
    std::vector<uint32_t> hull;
    if (places.empty()) return hull;
    auto chain = [&](auto visit_in_order) {
        const size_t base = hull.size();
        visit_in_order([&](uint32_t i) {
            while (hull.size() >= base + 2 && orient(places[hull[hull.size() - 2]], places[hull.back()], places[i]) <= 0)
                hull.pop_back();
            hull.push_back(i);
        });
        hull.pop_back();  // the other chain's first point
    };
    const uint32_t n = uint32_t(places.size());
    chain([&](auto visit) { for (uint32_t i = 0; i < n; ++i) visit(i); });
    chain([&](auto visit) { for (uint32_t i = n; i-- > 0;) visit(i); });
    return hull;
}

std::vector<uint32_t> KnownSamples::samplesBreaking(const Mesh& mesh, const PixelRect& rect,
                                                    const std::vector<uint32_t>& extra, const PixelRect& near) const {
    const PixelRect bounds = boundsOf(rect, extra);
    const int32_t dx = int32_t(bounds.x0) * kPositionOne, dy = int32_t(bounds.y0) * kPositionOne;
    auto at = [&](uint32_t v) {
        const Position p = positionOf(mesh, v);
        return Position{p.x + dx, p.y + dy};
    };
    const int32_t nx0 = int32_t(near.x0) * kPositionOne, nx1 = int32_t(near.x1 - 1) * kPositionOne;
    const int32_t ny0 = int32_t(near.y0) * kPositionOne, ny1 = int32_t(near.y1 - 1) * kPositionOne;
    // Whether the triangle or segment `ps` meets near's pixel centres' rectangle (separating
    // axes: the rectangle's, then each side's line with all four corners strictly beyond it).
    const Position corners[4] = {{nx0, ny0}, {nx1, ny0}, {nx0, ny1}, {nx1, ny1}};
    auto meetsNear = [&](std::initializer_list<Position> ps) {
        int32_t x0 = INT32_MAX, x1 = INT32_MIN, y0 = INT32_MAX, y1 = INT32_MIN;
        for (const Position& p : ps) x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
        if (x1 < nx0 || x0 > nx1 || y1 < ny0 || y0 > ny1) return false;
        if (x0 >= nx0 && x1 <= nx1 && y0 >= ny0 && y1 <= ny1) return true;  // inside: most triangles
        const Position* v = ps.begin();
        const size_t n = ps.size();
        for (size_t k = 0; k < n; ++k) {
            const Position &p = v[k], &q = v[(k + 1) % n];
            // A triangle (positive) lies left of each side; a segment on either side of its line.
            auto beyond = [&](int sign) {
                return std::all_of(std::begin(corners), std::end(corners),
                                   [&](const Position& c) { return orient(p, q, c) * sign > 0; });
            };
            if (beyond(-1) || (n == 2 && beyond(1))) return false;
        }
        return true;
    };
    const int32_t rx0 = int32_t(rect.x0) * kPositionOne, rx1 = int32_t(rect.x1 - 1) * kPositionOne;
    const int32_t ry0 = int32_t(rect.y0) * kPositionOne, ry1 = int32_t(rect.y1 - 1) * kPositionOne;
    auto taken = [&](uint32_t i) {
        const Position p = placeOf(i);
        return (p.x >= rx0 && p.x <= rx1 && p.y >= ry0 && p.y <= ry1) || std::binary_search(extra.begin(), extra.end(), i);
    };
    std::vector<uint32_t> breaking, candidates;
    forEachTriangle(mesh, [&](const Triangle& t) {
        Position a = at(t.v0), b = at(t.v1), c = at(t.v2);
        if (orient(a, b, c) < 0) std::swap(b, c);
        if (!meetsNear({a, b, c})) return;
        const Circle circle = circumcircleOf(a, b, c);
        if (circle.inside(rx0, ry0, rx1, ry1)) return;  // its samples are all taken
        candidates.clear();
        addSamplesNear(circle.x, circle.y, circle.radius, rect, candidates);
        for (uint32_t i : candidates)
            if (!taken(i) && inCircle(a, b, c, placeOf(i))) breaking.push_back(i);
    });
    for (const EdgeVertices& edge : mesh.vertices) {
        if (edge.l != kNone && edge.r != kNone) continue;
        const Position a = at(edge.a), b = at(edge.b);
        if (!meetsNear({a, b})) continue;
        // The edge's triangle is left of a→b when it is l: the outside is right of it. A corner
        // outside is no sample of the mesh (its hull holds them all).
        for (uint32_t corner : hull_) {
            const int64_t side = orient(a, b, placeOf(corner));
            if (edge.l != kNone ? side < 0 : side > 0) breaking.push_back(corner);
        }
    }
    std::sort(breaking.begin(), breaking.end());
    breaking.erase(std::unique(breaking.begin(), breaking.end()), breaking.end());
    return breaking;
}

}  // namespace ddt
