#include "square_input.h"

#include <algorithm>

namespace ddt {

Image squareInput(const Image& image, uint32_t size) {
    Image square;
    square.width = square.height = size;
    square.channels = image.channels;
    square.sample_type = image.sample_type;
    square.pixels.resize(size_t(size) * size * image.channels);
    auto source = [size](uint32_t i, uint32_t side) {
        if (size <= side) return (side - size) / 2 + i;
        const uint32_t period = 2 * side;  // reflect: 0 .. side−1, side−1 .. 0, ...
        const uint32_t j = i % period;
        return j < side ? j : period - 1 - j;
    };
    for (uint32_t y = 0; y < size; ++y) {
        const uint32_t sy = source(y, image.height);
        for (uint32_t x = 0; x < size; ++x) {
            const uint32_t sx = source(x, image.width);
            std::copy_n(image.pixels.data() + (size_t(sy) * image.width + sx) * image.channels, image.channels,
                        square.pixels.data() + (size_t(y) * size + x) * image.channels);
        }
    }
    return square;
}

}  // namespace ddt
