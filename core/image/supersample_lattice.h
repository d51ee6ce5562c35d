// The reconstruction's supersamples (core/image/reconstruct.h) on the grid's mesh, element by
// element: no sample is located and no weight is stored.
//
// The supersamples lie on the lattice of thirds of a pixel. A triangle of a triangulation that
// uses every pixel centre has twice-area 1 (Pick's theorem: no lattice point inside or on its
// sides but its corners), so the points of the thirds' lattice it holds are its corners, its
// sides' thirds and its centroid, with barycentric weights in thirds. So each supersample
// belongs to one vertex, one edge or one triangle, and the quadratic surface there is
//   a vertex's value                          at its pixel centre,
//   (2p + q)/3 + 8/9·b and (p + 2q)/3 + 8/9·b at the thirds of edge (p, q) with bubble b,
//   (v0 + v1 + v2)/3 + 4/9·(b0 + b1 + b2)     at a triangle's centroid.
// The ring of supersamples a third of a pixel outside the grid's rectangle takes the value of
// the nearest one inside, as a sample clamped into the hull does (core/image/raster.h).
//
// Every pass writes only what one element owns or gathers into one element's sum, in a fixed
// order, so the results do not depend on how the work is split across threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mesh.h"
#include "parallel.h"
#include "pixel_vector.h"
#include "uninitialised_vector.h"

namespace ddt {

class SupersampleLattice {
public:
    // The width × height grid's mesh (no explicit positions) as its edge records (taken over)
    // and its triangles (listTriangles' or a renderer's, any order; they must outlive this),
    // for surfaces of up to `channels` channels.
    SupersampleLattice(uint32_t width, uint32_t height, uint32_t channels, std::vector<EdgeVertices> edges,
                       const std::vector<Triangle>& triangles);

    // The supersampled grid: kSupersampling (3) samples per pixel and axis.
    uint32_t subWidth() const { return 3 * width_; }
    uint32_t subHeight() const { return 3 * height_; }
    uint32_t edgeCount() const { return uint32_t(edges_.size()); }

    // sub (subWidth × subHeight × c floats) = the surface with vertex values `values` (c per
    // vertex) and `bubbles` (c per edge) at every supersample.
    void evaluate(const float* values, const float* bubbles, uint32_t c, float* sub) const;

    // ⟨φ_u, g⟩ for every vertex value and bubble u, g given at the supersamples (C floats
    // each), handed to at_vertex(v, sum) and at_edge(e, sum) (PixelVector<C>) as each is
    // summed up, on the threads of core/parallel.h. g's outer ring is added into the ring
    // inside it (the transpose of the clamping), so g is changed. It works in the lattice's own
    // scratch: one call at a time.
    template <uint32_t C, typename AtVertex, typename AtEdge>
    void project(float* g, AtVertex at_vertex, AtEdge at_edge) const;

    static constexpr size_t kGrain = 4096;  // elements per task: each is a few loads and stores

private:
    // The basis functions at the lattice's points: a hat function is 2/3 or 1/3 at an edge's
    // thirds and 1/3 at a centroid; a bubble 4·λp·λq is 4 · 2/3 · 1/3 at its edge's thirds and
    // 4 · 1/3 · 1/3 at its triangles' centroids.
    static constexpr float kThird = 1.0f / 3.0f, kTwoThirds = 2.0f / 3.0f;
    static constexpr float kBubbleAtThird = 8.0f / 9.0f, kBubbleAtCentroid = 4.0f / 9.0f;
    // A vertex gathers each triangle around it from its two sides there: half of 1/3 from each.
    static constexpr float kHalfCentroid = 1.0f / 6.0f;

    // Supersample indices are linear in the place they sample, and vertex v's own is
    // 3·third_of_[v] + 1; so the one at the mean of two or three vertices' places (an edge's
    // third nearer p, a triangle's centroid) is a sum.
    size_t sampleOf(uint32_t v) const { return 3 * size_t(third_of_[v]) + 1; }
    size_t third(uint32_t p, uint32_t q) const { return 2 * size_t(third_of_[p]) + third_of_[q] + 1; }
    size_t centroid(uint32_t u, uint32_t v, uint32_t w) const {
        return size_t(third_of_[u]) + third_of_[v] + third_of_[w] + 1;
    }

    template <uint32_t C>
    void evaluateWith(const float* values, const float* bubbles, float* sub) const;
    void foldOuterRing(float* g, uint32_t c) const;

    uint32_t width_, height_, channels_;
    std::vector<EdgeVertices> edges_;
    const std::vector<Triangle>& triangles_;
    std::vector<uint32_t> third_of_;  // per vertex (below 3·w·h)
    // Edge e's shares of its a's and b's projections go to shares_[slot_of_[2e]] and
    // [slot_of_[2e + 1]] (`channels` floats each, left uninitialised until project writes them),
    // so that vertex v's lie together, in edge order: shares_[first_share_[v] .. first_share_[v + 1]).
    // The vertices then read their shares in one stream; read through an index, those loads
    // missed the caches and took most of the vertex pass's time.
    std::vector<uint32_t> first_share_;
    UninitialisedVector<uint32_t> slot_of_;
    mutable UninitialisedVector<float> shares_;
};

// Each edge sums its bubble's projection and its shares of its two vertices'; then each vertex
// its own sample and its shares.
template <uint32_t C, typename AtVertex, typename AtEdge>
void SupersampleLattice::project(float* g, AtVertex at_vertex, AtEdge at_edge) const {
    foldOuterRing(g, C);
    auto at = [&](size_t sample) { return loadPixel<C>(g + sample * C); };
    auto centroid = [&](uint32_t a, uint32_t b, uint32_t third) {  // none on the hull's side
        return third == kNone ? PixelVector<C>{} : at(this->centroid(a, b, third));
    };
    float* const shares = shares_.data();
    parallelFor(edges_.size(), kGrain, [&](size_t begin, size_t end) {
        for (size_t e = begin; e < end; ++e) {
            const EdgeVertices& r = edges_[e];
            const PixelVector<C> near_a = at(third(r.a, r.b)), near_b = at(third(r.b, r.a));
            const PixelVector<C> centroids = centroid(r.a, r.b, r.l) + centroid(r.a, r.b, r.r);
            at_edge(e, kBubbleAtThird * (near_a + near_b) + kBubbleAtCentroid * centroids);
            storePixel<C>(shares + size_t(slot_of_[2 * e]) * C,
                          kTwoThirds * near_a + kThird * near_b + kHalfCentroid * centroids);
            storePixel<C>(shares + size_t(slot_of_[2 * e + 1]) * C,
                          kThird * near_a + kTwoThirds * near_b + kHalfCentroid * centroids);
        }
    });
    parallelFor(size_t(width_) * height_, kGrain, [&](size_t begin, size_t end) {
        for (size_t v = begin; v < end; ++v) {
            PixelVector<C> sum = at(sampleOf(uint32_t(v)));
            for (uint32_t i = first_share_[v]; i < first_share_[v + 1]; ++i)
                sum += loadPixel<C>(shares + size_t(i) * C);
            at_vertex(v, sum);
        }
    });
}

}  // namespace ddt
