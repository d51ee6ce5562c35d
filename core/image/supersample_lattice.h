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
#include <memory>
#include <vector>

#include "mesh.h"

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

    // ⟨φ_u, g⟩ for every vertex value and bubble u, g given at the supersamples (c floats
    // each): c per vertex into vertex_sums, c per edge into edge_sums. g's outer ring is added
    // into the ring inside it (the transpose of the clamping), so g is changed. It works in
    // the lattice's own scratch: one call at a time.
    void project(float* g, uint32_t c, float* vertex_sums, float* edge_sums) const;

private:
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
    template <uint32_t C>
    void projectWith(float* g, float* vertex_sums, float* edge_sums) const;

    uint32_t width_, height_, channels_;
    std::vector<EdgeVertices> edges_;
    const std::vector<Triangle>& triangles_;
    std::vector<uint32_t> third_of_;  // per vertex (below 3·w·h)
    // Edge e's shares of its a's and b's projections go to shares_[2e] and [2e + 1] (`channels`
    // floats each, left uninitialised until project writes them). Vertex v gathers the shares
    // shared_[first_share_[v] .. first_share_[v + 1]), in edge order.
    std::vector<uint32_t> first_share_;
    std::unique_ptr<uint32_t[]> shared_;
    std::unique_ptr<float[]> shares_;
};

}  // namespace ddt
