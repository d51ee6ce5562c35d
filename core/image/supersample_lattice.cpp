#include "supersample_lattice.h"

#include <algorithm>
#include <cassert>

#include "channel_count.h"
#include "parallel.h"
#include "pixel_vector.h"

namespace ddt {

namespace {

// The basis functions at the lattice's points: a hat function is 2/3 or 1/3 at an edge's
// thirds and 1/3 at a centroid; a bubble 4·λp·λq is 4 · 2/3 · 1/3 at its edge's thirds and
// 4 · 1/3 · 1/3 at its triangles' centroids.
constexpr float kThird = 1.0f / 3.0f, kTwoThirds = 2.0f / 3.0f;
constexpr float kBubbleAtThird = 8.0f / 9.0f, kBubbleAtCentroid = 4.0f / 9.0f;
// A vertex gathers each triangle around it from its two sides there: half of 1/3 from each.
constexpr float kHalfCentroid = 1.0f / 6.0f;

// Elements per task: each is a few loads and stores.
const size_t kGrain = 4096;
// Rows of supersamples per task.
const size_t kRowGrain = 16;

}  // namespace

SupersampleLattice::SupersampleLattice(uint32_t width, uint32_t height, uint32_t channels,
                                       std::vector<EdgeVertices> edges, const std::vector<Triangle>& triangles)
    : width_(width), height_(height), channels_(channels), edges_(std::move(edges)), triangles_(triangles),
      third_of_(size_t(width) * height), shared_(std::make_unique_for_overwrite<uint32_t[]>(2 * edges_.size())),
      shares_(std::make_unique_for_overwrite<float[]>(2 * edges_.size() * channels)) {
    // Vertex (x, y)'s supersample is at column 3x + 1 and row 3y + 1 of the 3w-wide grid:
    // (3y + 1) · 3w + 3x + 1 = 3 · (3wy + w + x) + 1.
    parallelFor(height, kRowGrain, [&](size_t begin, size_t end) {
        for (uint32_t y = uint32_t(begin); y < end; ++y)
            for (uint32_t x = 0; x < width; ++x) third_of_[y * width + x] = 3 * width * y + width + x;
    });
    // Counted, summed, then given out in edge order. The vertices are split into ranges, one
    // per thread, each thread going through every edge for the ends in its range: so each
    // count and list is written by one thread, in edge order.
    const uint32_t vertices = width * height, ranges = std::max(1u, threadCount());
    auto forEachEnd = [&](auto f) {
        parallelFor(ranges, 1, [&](size_t begin, size_t end) {
            const uint32_t first = uint32_t(uint64_t(vertices) * begin / ranges);
            const uint32_t last = uint32_t(uint64_t(vertices) * end / ranges);
            for (uint32_t e = 0; e < edges_.size(); ++e) {
                if (edges_[e].a >= first && edges_[e].a < last) f(edges_[e].a, 2 * e);
                if (edges_[e].b >= first && edges_[e].b < last) f(edges_[e].b, 2 * e + 1);
            }
        });
    };
    first_share_.assign(vertices + 1, 0);
    forEachEnd([&](uint32_t v, uint32_t) { ++first_share_[v + 1]; });
    for (uint32_t v = 0; v < vertices; ++v) first_share_[v + 1] += first_share_[v];
    std::vector<uint32_t> next(first_share_.begin(), first_share_.end() - 1);
    forEachEnd([&](uint32_t v, uint32_t share) { shared_[next[v]++] = share; });
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
        const size_t last = end == height_;  // the last band takes what the proportion rounds off
        for (size_t e = edges * begin / height_, e_end = last ? edges : edges * end / height_; e < e_end; ++e) {
            const uint32_t a = edges_[e].a, b = edges_[e].b;
            const PixelVector<C> va = value(a), vb = value(b), lifted = kBubbleAtThird * bubble(uint32_t(e));
            store(third(a, b), kTwoThirds * va + kThird * vb + lifted);
            store(third(b, a), kThird * va + kTwoThirds * vb + lifted);
        }
        for (size_t i = triangles * begin / height_, i_end = last ? triangles : triangles * end / height_; i < i_end; ++i) {
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

void SupersampleLattice::project(float* g, uint32_t c, float* vertex_sums, float* edge_sums) const {
    assert(c <= channels_);
    withChannelCount(c, [&](auto channels) { projectWith<decltype(channels)::value>(g, vertex_sums, edge_sums); });
}

template <uint32_t C>
void SupersampleLattice::projectWith(float* g, float* vertex_sums, float* edge_sums) const {
    // The outer ring into the ring inside: the first and last rows, then each row's end columns
    // (a corner reaches the inner corner in two steps).
    const size_t sub_w = subWidth(), sub_h = subHeight();
    auto add = [](float* to, const float* from) { storePixel<C>(to, loadPixel<C>(to) + loadPixel<C>(from)); };
    parallelFor(sub_w, kGrain, [&](size_t begin, size_t end) {
        for (size_t x = begin; x < end; ++x) {
            add(g + (sub_w + x) * C, g + x * C);
            add(g + ((sub_h - 2) * sub_w + x) * C, g + ((sub_h - 1) * sub_w + x) * C);
        }
    });
    parallelFor(sub_h - 2, kRowGrain * 4, [&](size_t begin, size_t end) {
        for (size_t y = begin + 1; y < end + 1; ++y) {
            float* row = g + y * sub_w * C;
            add(row + C, row);
            add(row + (sub_w - 2) * C, row + (sub_w - 1) * C);
        }
    });
    auto at = [&](size_t sample) { return loadPixel<C>(g + sample * C); };
    // A triangle's centroid, or none on the hull's side.
    auto centroid = [&](uint32_t a, uint32_t b, uint32_t third) {
        return third == kNone ? PixelVector<C>{} : at(this->centroid(a, b, third));
    };
    // Each edge its bubble's sum and its shares of its vertices' sums; then each vertex its
    // sample and its shares.
    float* const shares = shares_.get();
    parallelFor(edges_.size(), kGrain, [&](size_t begin, size_t end) {
        for (size_t e = begin; e < end; ++e) {
            const EdgeVertices& r = edges_[e];
            const PixelVector<C> near_a = at(third(r.a, r.b)), near_b = at(third(r.b, r.a));
            const PixelVector<C> centroids = centroid(r.a, r.b, r.l) + centroid(r.a, r.b, r.r);
            storePixel<C>(edge_sums + e * C, kBubbleAtThird * (near_a + near_b) + kBubbleAtCentroid * centroids);
            storePixel<C>(shares + 2 * e * C, kTwoThirds * near_a + kThird * near_b + kHalfCentroid * centroids);
            storePixel<C>(shares + (2 * e + 1) * C,
                          kThird * near_a + kTwoThirds * near_b + kHalfCentroid * centroids);
        }
    });
    parallelFor(size_t(width_) * height_, kGrain, [&](size_t begin, size_t end) {
        for (size_t v = begin; v < end; ++v) {
            PixelVector<C> sum = at(sampleOf(uint32_t(v)));
            for (uint32_t i = first_share_[v]; i < first_share_[v + 1]; ++i)
                sum += loadPixel<C>(shares + size_t(shared_[i]) * C);
            storePixel<C>(vertex_sums + v * C, sum);
        }
    });
}

}  // namespace ddt
