#include "tiling.h"

#include <algorithm>
#include <cassert>

#include "raster.h"

namespace ddt {

namespace {

// Near-equal parts of [begin, end), none longer than `side`: the first part's end.
uint32_t firstPartEnd(uint32_t begin, uint32_t end, uint32_t side) {
    const uint64_t length = end - begin, parts = (length + side - 1) / side;
    return begin + uint32_t((length + parts - 1) / parts);
}

}  // namespace

uint32_t firstOutputOf(uint32_t c, uint32_t in_size, uint32_t out_size) {
    assert(c <= in_size);
    if (c == 0) return 0;
    if (c >= in_size) return out_size;
    return firstSampleAtOrAfter(c, in_size, out_size);
}

uint32_t stripEnd(uint32_t height, uint32_t y0, uint32_t side) {
    assert(y0 < height && side > 0);
    return firstPartEnd(y0, height, side);
}

uint32_t stripColumns(uint32_t width, uint32_t side, uint32_t at_once) {
    assert(side > 0);
    const uint32_t columns = (width + side - 1) / side;
    if (at_once <= 1 || columns <= 1 || columns % at_once == 0) return columns;
    const uint32_t rounded = (columns + at_once - 1) / at_once * at_once;
    return rounded <= width && width / rounded >= side / 2 ? rounded : columns;
}

std::vector<Tile> planStrip(uint32_t width, uint32_t height, OutputSize out, uint32_t y0, uint32_t y1, uint32_t side,
                            uint32_t overlap, uint32_t columns) {
    assert(y0 < y1 && y1 <= height && side > 0);
    if (columns == 0) columns = stripColumns(width, side, 1);
    assert(columns <= width);
    std::vector<Tile> tiles;
    for (uint32_t x0 = 0; x0 < width;) {
        // Near-equal parts of the columns left: for columns = ⌈width / side⌉ the cut that
        // firstPartEnd makes with `side`, part by part.
        const uint32_t parts = columns - uint32_t(tiles.size());
        const uint32_t x1 = x0 + (width - x0 + parts - 1) / parts;
        Tile tile;
        tile.core = {x0, y0, x1, y1};
        tile.crop = {x0 > overlap ? x0 - overlap : 0, y0 > overlap ? y0 - overlap : 0,
                     std::min<uint32_t>(width, x1 + overlap), std::min<uint32_t>(height, y1 + overlap)};
        tile.output = {firstOutputOf(x0, width, out.width), firstOutputOf(y0, height, out.height),
                       firstOutputOf(x1, width, out.width), firstOutputOf(y1, height, out.height)};
        tiles.push_back(tile);
        x0 = x1;
    }
    return tiles;
}

Image emptyCropOf(const Image& image, const PixelRect& rect) {
    Image crop;
    crop.width = rect.width();
    crop.height = rect.height();
    crop.channels = image.channels;
    crop.sample_type = image.sample_type;
    crop.pixels.resize(size_t(crop.width) * crop.height * crop.channels);
    return crop;
}

Image cropOf(const Image& image, const PixelRect& rect) {
    Image crop = emptyCropOf(image, rect);
    const size_t row_floats = size_t(crop.width) * crop.channels;
    for (uint32_t y = 0; y < crop.height; ++y)
        std::copy_n(image.row(rect.y0 + y) + size_t(rect.x0) * image.channels, row_floats,
                    crop.pixels.data() + y * row_floats);
    return crop;
}

}  // namespace ddt
