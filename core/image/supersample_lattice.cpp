#include "supersample_lattice.h"

#include <algorithm>
#include <cassert>

#include "channel_count.h"
#include "parallel.h"
#include "pixel_vector.h"

namespace ddt {

namespace {

// Rows of supersamples per task.
const size_t kRowGrain = 16;

}  // namespace

SupersampleLattice::SupersampleLattice(uint32_t width, uint32_t height, uint32_t channels,
                                       std::vector<EdgeVertices> edges, const std::vector<Triangle>& triangles)
    : width_(width), height_(height), channels_(channels), edges_(std::move(edges)), triangles_(triangles),
      third_of_(size_t(width) * height), slot_of_(2 * edges_.size()), shares_(2 * edges_.size() * channels) {
    // Vertex (x, y)'s supersample is at column 3x + 1 and row 3y + 1 of the 3w-wide grid:
    // (3y + 1) · 3w + 3x + 1 = 3 · (3wy + w + x) + 1.
    parallelFor(height, kRowGrain, [&](size_t begin, size_t end) {
        for (uint32_t y = uint32_t(begin); y < end; ++y)
            for (uint32_t x = 0; x < width; ++x) third_of_[y * width + x] = 3 * width * y + width + x;
    });
    // Counted, summed, then given out in edge order, in two passes over the edges: split over
    // threads by vertex ranges, each thread would read every edge.
    const uint32_t vertices = width * height;
    first_share_.assign(vertices + 1, 0);
    for (const EdgeVertices& r : edges_) {
        ++first_share_[r.a + 1];
        ++first_share_[r.b + 1];
    }
    for (uint32_t v = 0; v < vertices; ++v) first_share_[v + 1] += first_share_[v];
    std::vector<uint32_t> next(first_share_.begin(), first_share_.end() - 1);
    for (size_t e = 0; e < edges_.size(); ++e) {
        slot_of_[2 * e] = next[edges_[e].a]++;
        slot_of_[2 * e + 1] = next[edges_[e].b]++;
    }
}

void SupersampleLattice::evaluate(const float* values, const float* bubbles, uint32_t c, float* sub) const {
    assert(c <= channels_);
    withChannelCount(c, [&](auto channels) { evaluateWith<decltype(channels)::value>(values, bubbles, sub); });
}

template <uint32_t C>
void SupersampleLattice::evaluateWith(const float* values, const float* bubbles, float* sub) const {
    auto value = [&](uint32_t v) { return loadPixel<C>(values + size_t(v) * C); };
    auto bubble = [&](uint32_t e) { return loadPixel<C>(bubbles + size_t(e) * C); };
    auto store = [&](size_t sample, PixelVector<C> s) { storePixel<C>(sub + sample * C, s); };
    const size_t sub_w = subWidth(), sub_h = subHeight();
    // In bands of rows, each with the edges and triangles that lie about there (edge ids follow
    // the grid's vertices, three each; the triangles are sorted by top row), so that a band's
    // writes stay within a few rows of supersamples. Every element is written by one band.
    const size_t edges = edges_.size(), triangles = triangles_.size();
    parallelFor(height_, kRowGrain, [&](size_t begin, size_t end) {
        for (uint32_t y = uint32_t(begin); y < end; ++y)
            for (uint32_t v = y * width_; v < (y + 1) * width_; ++v) store(sampleOf(v), value(v));
        for (size_t e = edges * begin / height_; e < edges * end / height_; ++e) {
            const uint32_t a = edges_[e].a, b = edges_[e].b;
            const PixelVector<C> va = value(a), vb = value(b), lifted = kBubbleAtThird * bubble(uint32_t(e));
            store(third(a, b), kTwoThirds * va + kThird * vb + lifted);
            store(third(b, a), kThird * va + kTwoThirds * vb + lifted);
        }
        for (size_t i = triangles * begin / height_; i < triangles * end / height_; ++i) {
            const Triangle& t = triangles_[i];
            store(centroid(t.v0, t.v1, t.v2), kThird * (value(t.v0) + value(t.v1) + value(t.v2)) +
                                     kBubbleAtCentroid * (bubble(t.e0) + bubble(t.e1) + bubble(t.e2)));
        }
    });
    // The outer ring: each row's end columns, then the first and last rows whole.
    parallelFor(sub_h - 2, kRowGrain * 4, [&](size_t begin, size_t end) {
        for (size_t y = begin + 1; y < end + 1; ++y) {
            float* row = sub + y * sub_w * C;
            storePixel<C>(row, loadPixel<C>(row + C));
            storePixel<C>(row + (sub_w - 1) * C, loadPixel<C>(row + (sub_w - 2) * C));
        }
    });
    std::copy_n(sub + sub_w * C, sub_w * C, sub);
    std::copy_n(sub + (sub_h - 2) * sub_w * C, sub_w * C, sub + (sub_h - 1) * sub_w * C);
}

void SupersampleLattice::foldOuterRing(float* g, uint32_t c) const {
    assert(c <= channels_);
    // The first and last rows, then each row's end columns (a corner reaches the inner corner
    // in two steps).
    const size_t sub_w = subWidth(), sub_h = subHeight();
    auto add = [c](float* to, const float* from) {
        for (uint32_t k = 0; k < c; ++k) to[k] += from[k];
    };
    parallelFor(sub_w, kGrain, [&](size_t begin, size_t end) {
        for (size_t x = begin; x < end; ++x) {
            add(g + (sub_w + x) * c, g + x * c);
            add(g + ((sub_h - 2) * sub_w + x) * c, g + ((sub_h - 1) * sub_w + x) * c);
        }
    });
    parallelFor(sub_h - 2, kRowGrain * 4, [&](size_t begin, size_t end) {
        for (size_t y = begin + 1; y < end + 1; ++y) {
            float* row = g + y * sub_w * c;
            add(row + c, row);
            add(row + (sub_w - 2) * c, row + (sub_w - 1) * c);
        }
    });
}

}  // namespace ddt
