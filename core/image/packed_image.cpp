#include "packed_image.h"

#include <cassert>
#include <utility>

#include "parallel.h"

namespace ddt {

PackedImage::PackedImage(Image image) : header_(std::move(image)) {}

PackedImage::PackedImage(Image header, std::vector<uint8_t> codes, std::vector<float> values, bool straight_alpha)
    : header_(std::move(header)), codes8_(std::move(codes)), values_(std::move(values)), straight_alpha_(straight_alpha) {
    header_.pixels = {};
    assert(values_.size() == 256);
}

PackedImage::PackedImage(Image header, std::vector<uint16_t> codes, std::vector<float> values, bool straight_alpha)
    : header_(std::move(header)), codes16_(std::move(codes)), values_(std::move(values)), straight_alpha_(straight_alpha) {
    header_.pixels = {};
    assert(values_.size() == 65536);
}

template <class Code>
void PackedImage::unpackRows(const std::vector<Code>& codes, const PixelRect& rect, float* out) const {
    const uint32_t c = header_.channels;
    const size_t row_samples = size_t(rect.width()) * c;
    for (uint32_t y = rect.y0; y < rect.y1; ++y) {
        const Code* in = codes.data() + (size_t(y) * header_.width + rect.x0) * c;
        for (size_t i = 0; i < row_samples; ++i) out[i] = values_[in[i]];
        if (straight_alpha_) premultiply(out, row_samples, c);
        out += row_samples;
    }
}

Image PackedImage::crop(const PixelRect& rect) const {
    if (floats()) return cropOf(header_, rect);
    Image crop = emptyCropOf(header_, rect);
    if (!codes8_.empty()) unpackRows(codes8_, rect, crop.pixels.data());
    else unpackRows(codes16_, rect, crop.pixels.data());
    return crop;
}

Image PackedImage::unpack() && {
    if (floats()) return std::move(header_);
    Image image = header_;
    image.pixels.resize(size_t(image.width) * image.height * image.channels);
    // A band of rows per task: each row's floats are written by one thread.
    parallelFor(image.height, 16, [&](size_t begin, size_t end) {
        const PixelRect rows{0, uint32_t(begin), image.width, uint32_t(end)};
        float* out = image.pixels.data() + begin * image.rowFloats();
        if (!codes8_.empty()) unpackRows(codes8_, rows, out);
        else unpackRows(codes16_, rows, out);
    });
    codes8_ = {};
    codes16_ = {};
    return image;
}

void PackedImage::release() {
    header_.pixels = {};
    codes8_ = {};
    codes16_ = {};
}

size_t PackedImage::bytes() const {
    return codes8_.size() + codes16_.size() * sizeof(uint16_t) + header_.pixels.size() * sizeof(float);
}

}  // namespace ddt
