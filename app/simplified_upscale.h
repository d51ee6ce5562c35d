// `--simplify R`: the image is optimized whole, its mesh simplified to a fraction R of the
// vertices by the backend (Backend::simplify: the serial greedy simplifier on the CPU, the
// parallel rule on a device), and the output is rendered from that mesh by the same
// exact-coverage renderer: the surface linear on each triangle, with each vertex's best colour.
//
// The flips do not run again on the simplified mesh: measured, Sederberg's cost made it worse
// (PSNR against the original at ×4 from quarter size, 10 % of the vertices: astronaut 23.20 dB
// without, 22.66 with the flips again; chelsea 27.51 / 26.84; building 23.39 / 22.86; at the
// original's size, astronaut at 20 %: 41.01 / 39.04), also with the cost taken on the
// vertices' best colours (22.72, 26.78, 22.90). The consistent reconstruction (core/image/reconstruct.h) does not fit coarse
// meshes: it keeps each vertex within its 3 × 3 pixels' range, and measured on the astronaut
// at ×4 (128² → 512², PSNR against the original) it scored 21.3 dB at 10 % of the vertices
// where the linear surface scores 22.7 dB.
//
// An image whose simplification does not fit the memory whole (greedy_simplify.h counts about
// 800 bytes a pixel: 18 GiB for 24 MP), or that --tile asks to cut, is simplified in tiles:
// cores that partition the input (core/image/tiling.h), each tile's mesh built on its core and
// the next tiles' first column and row, so that neighbours share those lines. Each tile is
// optimized and simplified alone, two at a time on the CPU, with its shared sides locked
// (Mesh::locked_sides): their vertices stay, with their pixels' colours, so the tiles' meshes
// meet on the same vertices and the surface is continuous across them. Each tile keeps the
// fraction of its own core's vertices, so the fraction holds overall; the locked lines spend
// about 2/side of the vertices (0.4 % for 512-pixel tiles, a 25th of a 10 % share).
#pragma once

#include <functional>
#include <vector>

#include "greedy_simplify.h"
#include "tiled_upscale.h"
#include "tiling.h"

namespace ddt {

struct SimplifiedUpscale {
    OptimizeStats optimize;   // the backend's optimization, summed over the tiles
    ParallelSimplifyStats simplify;  // rounds: 0 where the serial simplifier ran; vertices counted once
    Image values;             // the vertices' colours (greedy_simplify.h): what a mesh file holds; empty when tiled
};

// The tile side a width × height simplification is cut into: 0 when it goes whole (it fits the
// backend's memoryLimit and --tile does not ask for smaller tiles), else --tile's side or
// kSimplifyTileSide, halved until the tiles in flight fit (UserError if kMinTileSide does not).
constexpr uint32_t kSimplifyTileSide = 512;
uint32_t simplifyTileSide(const Backend& backend, uint32_t width, uint32_t height, uint32_t channels, uint32_t tile);

// The first output index (column or row) whose sample lies at or after input coordinate c,
// 0 <= c <= in_size, once snapped to the positions' grid as a mesh with explicit positions
// samples (core/image/render.h). Tiles own their output pixels by these samples: a sample just
// before a core's end, snapped onto the next core's first line, goes to the next tile, whose
// mesh the tie rule pushes it into (it would fall off the first tile's).
uint32_t firstSnappedOutputOf(uint32_t c, uint32_t in_size, uint32_t out_size);

// A tile of a simplification: its core (tiling.h), its crop (the core and the next tiles'
// first column and row), the output pixels it renders, and once simplified its mesh (with
// explicit positions; the shared sides locked) and the vertices' colours.
struct SimplifiedTile {
    PixelRect core, crop, output;
    Mesh mesh;
    Image values;
    uint32_t shared = 0;  // its crop's vertices in the next tiles' cores, counted there
};

// The tiles of the strip of input rows [y0, y1) (stripEnd), at most `side` pixels a side.
std::vector<SimplifiedTile> planSimplifiedStrip(uint32_t width, uint32_t height, OutputSize out, uint32_t y0, uint32_t y1,
                                                uint32_t side);

// Optimizes `tile`'s crop of `image` on `backend` and simplifies its mesh to `fraction` of its
// core's vertices (its shared ones on top) or as far as `max_error` allows. Returns the
// simplification's statistics, its shared vertices left out; `optimized` gets the optimization's.
ParallelSimplifyStats simplifyTile(Backend& backend, const Image& image, SimplifiedTile& tile, double fraction,
                                   double max_error, OptimizeStats& optimized);

// The vertices `fraction` of a width × height image's asks for: at least the four corners.
uint32_t simplifiedVertexCount(uint32_t width, uint32_t height, double fraction);

// `fraction` of the vertices (0: down to the corners) or as far as `max_error` allows
// (greedy_simplify.h; 0: no limit).
SimplifiedUpscale upscaleSimplified(Backend& backend, const Image& image, OutputSize out, double fraction, double max_error,
                                    const TileOptions& options, const std::function<void(OutputRows&& rows)>& sink,
                                    const TileStepCallback& on_step = {});

}  // namespace ddt
