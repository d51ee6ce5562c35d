#include "supersample_lattice.h"

#include <cassert>

#include "channel_count.h"
#include "divide_by.h"
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
                                       const std::vector<EdgeVertices>& edges, const std::vector<Triangle>& triangles)
    : width_(width), height_(height), channels_(channels), edge_count_(uint32_t(edges.size())),
      edges_(std::make_unique_for_overwrite<EdgeSamples[]>(edges.size())), triangles_(triangles),
      centroids_(std::make_unique_for_overwrite<uint32_t[]>(triangles.size())),
      shares_(std::make_unique_for_overwrite<float[]>(2 * edges.size() * channels)) {
    // Where a point of the lattice lies, from sums of vertex columns and rows, in thirds of a
    // pixel from vertex 0's pixel centre.
    const DivideBy by_width(width);
    const uint32_t sub_w = subWidth();
    auto at = [sub_w](uint32_t x, uint32_t y) { return (y + 1) * sub_w + x + 1; };
    auto column = [&](uint32_t v) { return v - by_width.quotient(v) * width; };
    auto row = [&](uint32_t v) { return by_width.quotient(v); };
    parallelFor(edges.size(), kGrain, [&](size_t begin, size_t end) {
        for (size_t e = begin; e < end; ++e) {
            const EdgeVertices& r = edges[e];
            const uint32_t ax = column(r.a), ay = row(r.a), bx = column(r.b), by = row(r.b);
            auto centroid = [&](uint32_t third) {
                return third == kNone ? kNone : at(ax + bx + column(third), ay + by + row(third));
            };
            edges_[e] = {r.a, r.b, at(2 * ax + bx, 2 * ay + by), at(ax + 2 * bx, ay + 2 * by), centroid(r.l), centroid(r.r), 0, 0};
        }
    });
    parallelFor(triangles.size(), kGrain, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            const Triangle& t = triangles[i];
            centroids_[i] = at(column(t.v0) + column(t.v1) + column(t.v2), row(t.v0) + row(t.v1) + row(t.v2));
        }
    });
    // Counted, summed, then given out in edge order.
    const uint32_t vertices = width * height;
    first_slot_.assign(vertices + 1, 0);
    for (const EdgeVertices& e : edges) {
        ++first_slot_[e.a + 1];
        ++first_slot_[e.b + 1];
    }
    for (uint32_t v = 0; v < vertices; ++v) first_slot_[v + 1] += first_slot_[v];
    std::vector<uint32_t> next(first_slot_.begin(), first_slot_.end() - 1);
    for (uint32_t e = 0; e < edge_count_; ++e) {
        edges_[e].slot_a = next[edges_[e].a]++;
        edges_[e].slot_b = next[edges_[e].b]++;
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
    auto store = [&](uint32_t sample, PixelVector<C> s) { storePixel<C>(sub + size_t(sample) * C, s); };
    const size_t sub_w = subWidth(), sub_h = subHeight();
    parallelFor(height_, kRowGrain, [&](size_t begin, size_t end) {
        for (uint32_t y = uint32_t(begin); y < end; ++y)
            for (uint32_t x = 0; x < width_; ++x) store(uint32_t((3 * y + 1) * sub_w + 3 * x + 1), value(y * width_ + x));
    });
    parallelFor(edge_count_, kGrain, [&](size_t begin, size_t end) {
        for (size_t e = begin; e < end; ++e) {
            const EdgeSamples& r = edges_[e];
            const PixelVector<C> va = value(r.a), vb = value(r.b), lifted = kBubbleAtThird * bubble(uint32_t(e));
            store(r.near_a, kTwoThirds * va + kThird * vb + lifted);
            store(r.near_b, kThird * va + kTwoThirds * vb + lifted);
        }
    });
    parallelFor(triangles_.size(), kGrain, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            const Triangle& t = triangles_[i];
            store(centroids_[i], kThird * (value(t.v0) + value(t.v1) + value(t.v2)) +
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
    auto at = [&](uint32_t sample) { return loadPixel<C>(g + size_t(sample) * C); };
    // A centroid's share, or none on the hull's side.
    auto centroid = [&](uint32_t sample) { return sample == kNone ? PixelVector<C>{} : at(sample); };
    // Each edge its bubble's sum and its shares of its vertices' sums; then each vertex its
    // sample and its shares.
    float* const shares = shares_.get();
    parallelFor(edge_count_, kGrain, [&](size_t begin, size_t end) {
        for (size_t e = begin; e < end; ++e) {
            const EdgeSamples& r = edges_[e];
            const PixelVector<C> near_a = at(r.near_a), near_b = at(r.near_b);
            const PixelVector<C> centroids = centroid(r.left) + centroid(r.right);
            storePixel<C>(edge_sums + e * C, kBubbleAtThird * (near_a + near_b) + kBubbleAtCentroid * centroids);
            storePixel<C>(shares + size_t(r.slot_a) * C, kTwoThirds * near_a + kThird * near_b + kHalfCentroid * centroids);
            storePixel<C>(shares + size_t(r.slot_b) * C, kThird * near_a + kTwoThirds * near_b + kHalfCentroid * centroids);
        }
    });
    parallelFor(height_, kRowGrain, [&](size_t begin, size_t end) {
        for (uint32_t y = uint32_t(begin); y < end; ++y)
            for (uint32_t x = 0, v = y * width_; x < width_; ++x, ++v) {
                PixelVector<C> sum = at(uint32_t((3 * y + 1) * sub_w + 3 * x + 1));
                for (uint32_t i = first_slot_[v]; i < first_slot_[v + 1]; ++i) sum += loadPixel<C>(shares + size_t(i) * C);
                storePixel<C>(vertex_sums + size_t(v) * C, sum);
            }
    });
}

}  // namespace ddt
