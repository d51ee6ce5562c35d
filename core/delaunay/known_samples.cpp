#include "known_samples.h"

#include <algorithm>
#include <cmath>

#include "parallel.h"

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

PixelRect KnownSamples::boundsOf(const PixelRect& rect, const std::vector<uint32_t>&) const { return rect; }

std::vector<uint32_t> KnownSamples::samplesBreaking(const Mesh&, const PixelRect&, const std::vector<uint32_t>&,
                                                    const PixelRect&) const {
    return {};
}

}  // namespace ddt
