// A mask's known pixels as one byte a pixel, and the crop a tile of them needs so that its
// Delaunay triangulation equals the whole image's where the tile renders.
//
// Why a crop can be exact. A triangle of the whole triangulation has an empty circumcircle:
// no known pixel inside. It stays empty among fewer points, so every whole-image triangle with
// its three vertices in a crop is also a triangle of the crop's triangulation; if such
// triangles cover a region, the crop's triangulation there is the whole one. An empty circle
// of radius r centred at c has no known pixel nearer to c than r: r <= d(c), the distance from
// c to the nearest known pixel. So a triangle meeting a region R lies within r of its centre
// and its centre within r of R: inside R grown by 2r. If the crop is R grown by g, with
// g >= 2·(m + 1) + 1 and m the largest d of a pixel in R grown by g (+1 for a centre between
// pixels, +1 spare), every triangle meeting R lies in the crop; a centre beyond R + g would
// need a pixel on its way in with d >= g - 1 > m. A long thin scratch asks for little (m is
// half its width), a wide blob for its width.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tiling.h"

namespace ddt {

class KnownPixels {
public:
    KnownPixels() = default;
    // `known`: width × height bytes, row-major, non-zero where the pixel is known.
    KnownPixels(uint32_t width, uint32_t height, std::vector<uint8_t> known);

    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    bool known(uint32_t x, uint32_t y) const { return known_[size_t(y) * width_ + x] != 0; }
    // The known pixels of `rect` as ids of the rect's own grid, (y − y0)·width + (x − x0), ascending.
    std::vector<uint32_t> idsIn(const PixelRect& rect) const;
    // Why the known pixels of `rect` have no triangulation ("fewer than 3 points", "all points
    // are collinear", as delaunayInputProblem says), "" if they have one.
    std::string problemIn(const PixelRect& rect) const;

    // `rect` grown, within the image, until the rule above holds for it (or by at most
    // `max_growth` pixels a side: wider holes may then triangulate differently near the crop's
    // border); the whole image where that crop's known pixels have no triangulation (problemIn).
    // Needs measureHoles() first.
    PixelRect cropFor(const PixelRect& rect, uint32_t max_growth) const;
    // Finds each block's largest distance to a known pixel (exact Euclidean distance
    // transform); holds 4 bytes a pixel while it runs.
    void measureHoles();

private:
    // The largest distance to a known pixel over the blocks `rect` touches (an upper bound).
    float largestDistanceIn(const PixelRect& rect) const;

    uint32_t width_ = 0, height_ = 0;
    std::vector<uint8_t> known_;
    uint32_t block_columns_ = 0;
    std::vector<float> block_distance_;  // per kBlock × kBlock block, row-major
};

}  // namespace ddt
