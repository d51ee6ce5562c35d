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

#include <cstdint>
#include <memory>
#include <vector>

#include "mesh.h"

namespace ddt {

class SupersampleLattice {
public:
    // The width × height grid's mesh (no explicit positions) as its edge records and its
    // triangles (listTriangles' or a renderer's, any order; they must outlive this), for
    // surfaces of up to `channels` channels.
    SupersampleLattice(uint32_t width, uint32_t height, uint32_t channels, const std::vector<EdgeVertices>& edges,
                       const std::vector<Triangle>& triangles);

    // The supersampled grid: kSupersampling (3) samples per pixel and axis.
    uint32_t subWidth() const { return 3 * width_; }
    uint32_t subHeight() const { return 3 * height_; }
    uint32_t edgeCount() const { return edge_count_; }

    // sub (subWidth × subHeight × c floats) = the surface with vertex values `values` (c per
    // vertex) and `bubbles` (c per edge) at every supersample.
    void evaluate(const float* values, const float* bubbles, uint32_t c, float* sub) const;

    // ⟨φ_u, g⟩ for every vertex value and bubble u, g given at the supersamples (c floats
    // each): c per vertex into vertex_sums, c per edge into edge_sums. g's outer ring is added
    // into the ring inside it (the transpose of the clamping), so g is changed.
    void project(float* g, uint32_t c, float* vertex_sums, float* edge_sums) const;

private:
    // An edge's endpoints; the supersamples it reaches: its thirds (the one near a, the one
    // near b) and the centroids of its triangles (kNone for a side on the hull); and where its
    // shares of a's and b's projections go among the vertices' shares.
    struct EdgeSamples {
        uint32_t a, b;
        uint32_t near_a, near_b, left, right;
        uint32_t slot_a, slot_b;
    };

    template <uint32_t C>
    void evaluateWith(const float* values, const float* bubbles, float* sub) const;
    template <uint32_t C>
    void projectWith(float* g, float* vertex_sums, float* edge_sums) const;

    uint32_t width_, height_, channels_, edge_count_;
    // The large arrays are left uninitialised and first written by the parallel passes.
    std::unique_ptr<EdgeSamples[]> edges_;
    const std::vector<Triangle>& triangles_;
    std::unique_ptr<uint32_t[]> centroids_;  // per triangle of triangles_
    // Each vertex's shares from its edges, in edge order, are slots [first_slot_[v],
    // first_slot_[v + 1]); project keeps them in shares_, `channels` floats per slot.
    std::vector<uint32_t> first_slot_;
    std::unique_ptr<float[]> shares_;
};

}  // namespace ddt
