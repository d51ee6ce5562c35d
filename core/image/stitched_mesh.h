// One triangulation of the whole input's pixel grid from the meshes of its tiles (core/image/tiling.h),
// for the mesh files (`--mesh`) of images optimised in tiles.
//
// Each tile gives the triangles of its crop's mesh whose centroid lies in its core; the cores
// partition the input, so every triangle of the untiled mesh would be given once. Where the
// tiles' meshes agree near the core borders (the overlap makes them agree: core/image/tiling.h), the
// union is a triangulation of the grid; where they do not, check() finds it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mesh.h"
#include "tiling.h"

namespace ddt {

class StitchedMesh {
public:
    StitchedMesh(uint32_t width, uint32_t height) : width_(width), height_(height) {}

    // Adds the triangles of `mesh`, built on `crop` of the input, whose centroids lie in `core`.
    // Not thread-safe: tiles in parallel take turns. A mesh with explicit positions (a
    // simplified one) must be the whole input's.
    void add(const Mesh& mesh, const PixelRect& crop, const PixelRect& core);

    // Adds the triangles of `other` (a strip's, once the strip succeeded).
    void append(StitchedMesh&& other);

    // The triangles, three whole-input vertex ids each, each rotated to start at its smallest id
    // and sorted: the same list whatever the tiles and the order they came in.
    std::vector<uint32_t> take();
    // The explicit positions of the mesh added, per vertex id (empty: pixel centres).
    std::vector<Position> takePositions() { return std::move(positions_); }

    // "" if the triangles tile the input's rectangle of pixel centres exactly once, else what
    // is wrong. Sufficient: every triangle positive, every directed edge in one triangle at
    // most, and each edge's reverse in another triangle unless the edge runs along the
    // rectangle's border. Then crossing an inner edge never changes how often a point is
    // covered, so every inner point is covered equally often, and the total area, which is
    // checked too, makes that once. At `positions` if given (explicit, per vertex id), else at
    // the pixel centres.
    static std::string check(const std::vector<uint32_t>& triangles, uint32_t width, uint32_t height,
                             const std::vector<Position>& positions = {});

private:
    uint32_t width_, height_;
    std::vector<uint32_t> triangles_;
    std::vector<Position> positions_;
};

}  // namespace ddt
