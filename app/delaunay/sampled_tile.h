// One tile of a masked image (--mask with tiles, app/tiled_upscale.h): the known pixels of the
// tile's crop are triangulated and optimized on their own, and the tile renders only its
// output. The crop is grown until the triangulation equals the whole image's where the tile
// renders (core/delaunay/known_pixels.h), so tiles of holes that fit their crops join without
// seams. Outside the crop's hull (a hole on the image's border) each output pixel takes the
// nearest rendered one, searched in the output of the crop, not of the whole image.
#pragma once

#include <memory>

#include "backend.h"
#include "known_pixels.h"
#include "packed_image.h"
#include "tiling.h"

namespace ddt {

struct SampledTile {
    std::unique_ptr<HostSurface> surface;  // renders windows of the tile's output
    OptimizeStats stats;
};

// Triangulates the known pixels of `tile.crop` (on `backend`, which --delaunay may place on its
// device), optimizes that mesh there and hands over its surface. `frame`: the whole input's
// size and the output's (its crop offset and rows unused).
SampledTile shapeSampledTile(Backend& backend, const PackedImage& input, const KnownPixels& known, const Tile& tile,
                             const RenderWindow& frame);

}  // namespace ddt
