#include "raw_image.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <vector>

namespace ddt {

RawSize parseRawSize(const std::string& text) {
    RawSize size;
    char x1 = 0, x2 = 0, rest = 0;
    if (std::sscanf(text.c_str(), "%u%c%u%c%u%c", &size.width, &x1, &size.height, &x2, &size.channels, &rest) != 5 ||
        x1 != 'x' || x2 != 'x' || size.channels < 1 || size.channels > 4 || size.width < 2 || size.height < 2 ||
        uint64_t(size.width) * size.height > kMaxInputPixels)
        throw UserError("--raw-size " + text + ": expected WxHxC with W, H at least 2, C 1 to 4, W·H at most 2^28");
    return size;
}

Image readRawImage(const std::string& path, RawSize size) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw UserError(path + ": cannot open");
    const std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
    const size_t expected = size_t(size.width) * size.height * size.channels;
    if (bytes.size() != expected)
        throw UserError(path + ": " + std::to_string(bytes.size()) + " bytes, but " + std::to_string(size.width) + "x" +
                        std::to_string(size.height) + "x" + std::to_string(size.channels) + " needs " +
                        std::to_string(expected));
    Image image;
    image.width = size.width;
    image.height = size.height;
    image.channels = size.channels;
    image.sample_type = SampleType::UInt8;
    image.pixels.resize(expected);
    for (size_t i = 0; i < expected; ++i) image.pixels[i] = float(bytes[i]) / 255.0f;
    if (image.hasAlpha())
        for (float* pixel = image.pixels.data(); pixel < image.pixels.data() + expected; pixel += size.channels)
            for (uint32_t k = 0; k + 1 < size.channels; ++k) pixel[k] *= pixel[size.channels - 1];
    return image;
}

}  // namespace ddt
