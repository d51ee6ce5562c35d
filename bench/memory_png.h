// PNG files held in memory. The bench's init stage decodes the low-resolution input from
// one, so that it times a real load without letting the disk into the measurement.
#pragma once

#include <cstdint>
#include <vector>

#include "image_file.h"

namespace bench {

struct PngInMemory {
    std::vector<unsigned char> bytes;
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t channels = 0;
};

// `image` (grey or RGB) as an 8-bit PNG.
PngInMemory encodePng(const ddt::Image& image);

// The image in `png`, values in [0, 1] like ddt::readImage.
ddt::Image decodePng(const PngInMemory& png);

}  // namespace bench
