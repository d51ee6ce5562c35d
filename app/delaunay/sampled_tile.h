// One tile of known samples (--mask or a point file with tiles, app/tiled_upscale.h): the
// samples of the tile's crop are triangulated and optimized on their own, and the tile renders
// only its output. The crop is grown until the triangulation equals the whole frame's where the
// tile renders (core/delaunay/known_samples.h), so tiles of gaps that fit their crops join
// without seams. Outside the crop's hull (a gap on the frame's border) each output pixel takes
// the nearest rendered one, searched in the output of the crop, not of the whole frame.
#pragma once

#include <memory>

#include "backend.h"
#include "known_samples.h"
#include "packed_image.h"
#include "tiling.h"

namespace ddt {

// The overlap of a point file's tiles (TileOptions::overlap). The flips on scattered points
// reach further than on the grid: 2048² with 10 % of its pixels as random points, ×1 and ×2,
// tiles of 128 and 256 against one piece: overlap 16 leaves 2 to 39 differing pixels, 24 and
// 32 none.
constexpr uint32_t kPointTileOverlap = 32;

struct SampledTile {
    std::unique_ptr<HostSurface> surface;  // renders windows of the tile's output
    OptimizeStats stats;
};

// Triangulates the samples of `tile.crop` (on `backend`, which --delaunay may place on its
// device), optimizes that mesh there and hands over its surface. `input`: a mask's image (a
// point file's header only); `frame`: the whole input's size and the output's (its crop offset
// and rows unused); `overlap`: the tiles' (TileOptions::overlap), how far around its core the
// tile's triangulation is checked (KnownSamples::samplesBreaking).
SampledTile shapeSampledTile(Backend& backend, const PackedImage& input, const KnownSamples& known, const Tile& tile,
                             const RenderWindow& frame, uint32_t overlap);

}  // namespace ddt
