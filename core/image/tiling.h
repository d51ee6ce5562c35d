// Tiles for inputs too large for the device: the input is split into cores, rectangles that
// partition it; each tile's mesh is built and optimised on its crop (the core grown by an
// overlap, clamped to the input) and renders only the output pixels whose samples lie in its
// core. The overlap lets the flips near a core's border see the same neighbourhood as in the
// untiled mesh, so seams vanish (the agreement per overlap is measured in test/image/test_tiling.cpp).
//
// Ownership of output pixels uses the renderer's exact sampling (glsl/raster.h): output
// column X belongs to the core [x0, x1) whose columns hold its clamped sample, i.e.
// firstOutputOf(x0) <= X < firstOutputOf(x1); rows alike. So every output pixel belongs to
// exactly one tile, with no gaps or doubles at core borders.
//
// Tiles are planned one strip (a row of tiles) at a time, so that a retry with smaller
// tiles can restart at the strip that failed.
#pragma once

#include <cstdint>
#include <vector>

#include "render.h"

namespace ddt {

// [x0, x1) × [y0, y1) in pixels.
struct PixelRect {
    uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;

    uint32_t width() const { return x1 - x0; }
    uint32_t height() const { return y1 - y0; }
};

// The pixels of `image` inside `rect`, as an image of their own (a tile's crop).
Image cropOf(const Image& image, const PixelRect& rect);
// A crop's image of `image`'s channels and sample type, its pixels allocated but not filled.
Image emptyCropOf(const Image& image, const PixelRect& rect);

struct Tile {
    PixelRect core;    // input pixels the tile answers for
    PixelRect crop;    // input pixels its mesh is built on: the core grown by the overlap
    PixelRect output;  // output pixels whose samples lie in the core
};

// The first output index (column or row) whose sample lies at or after input coordinate
// `c`, for 0 <= c <= in_size: 0 for c = 0, out_size for c = in_size.
uint32_t firstOutputOf(uint32_t c, uint32_t in_size, uint32_t out_size);

// The end row of the strip that starts at input row y0 when tiles are `side` rows tall: the
// rest of the input is cut into near-equal strips, none taller than `side`.
uint32_t stripEnd(uint32_t height, uint32_t y0, uint32_t side);

// The tiles of the strip of input rows [y0, y1): its columns cut into near-equal cores of at
// most `side` columns, left to right; or into `columns` near-equal cores where given (0: as
// many as `side` asks for, stripColumns(width, side, 1)).
std::vector<Tile> planStrip(uint32_t width, uint32_t height, OutputSize out, uint32_t y0, uint32_t y1, uint32_t side,
                            uint32_t overlap, uint32_t columns = 0);

// The cores a strip of `width` columns is cut into for tiles of at most `side`. Where `at_once`
// tiles run side by side, their count is rounded up to a multiple of at_once, so that the
// strip's last round keeps every thread busy, as long as the cores stay at least half the side
// (always, for two threads and three or more columns).
uint32_t stripColumns(uint32_t width, uint32_t side, uint32_t at_once);

}  // namespace ddt
