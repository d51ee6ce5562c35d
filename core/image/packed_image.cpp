#include "packed_image.h"

#include <algorithm>
#include <cassert>
#include <stdexcept>
#include <utility>

#include "parallel.h"

namespace ddt {

PackedImage::PackedImage(Image image) : header_(std::move(image)), decoded_rows_(header_.height) {}

PackedImage::PackedImage(Image header, std::vector<uint8_t> codes, std::vector<float> values, bool straight_alpha)
    : header_(std::move(header)), codes8_(std::move(codes)), values_(std::move(values)), straight_alpha_(straight_alpha),
      decoded_rows_(header_.height) {
    header_.pixels = {};
    assert(values_.size() == 256);
}

PackedImage::PackedImage(Image header, std::vector<uint16_t> codes, std::vector<float> values, bool straight_alpha)
    : header_(std::move(header)), codes16_(std::move(codes)), values_(std::move(values)), straight_alpha_(straight_alpha),
      decoded_rows_(header_.height) {
    header_.pixels = {};
    assert(values_.size() == 65536);
}

PackedImage::PackedImage(Image header, std::unique_ptr<RowDecoder> rows, std::vector<float> values, bool straight_alpha)
    : header_(std::move(header)), values_(std::move(values)), straight_alpha_(straight_alpha), rows_(std::move(rows)) {
    header_.pixels = {};
    assert(values_.size() == 256 || values_.size() == 65536);
}

template <class Code>
void PackedImage::decodeHeldRows(std::vector<Code>& codes, uint32_t y0, uint32_t y1) {
    const size_t row_samples = size_t(header_.width) * header_.channels;
    // Rows are decoded in order: asked to skip ahead, the window starts at the first row not
    // yet decoded (the tiles' strips overlap, so they never skip).
    const uint32_t first = std::min(y0, decoded_rows_), end = std::max(y1, decoded_rows_);
    // A new vector of the window's exact size: the rows kept move to its front.
    std::vector<Code> held((end - first) * row_samples);
    std::copy(codes.begin() + (first - first_row_) * row_samples, codes.end(), held.begin());
    if (end > decoded_rows_) rows_->decodeRows(end - decoded_rows_, held.data() + (decoded_rows_ - first) * row_samples);
    codes = std::move(held);
    first_row_ = first;
    decoded_rows_ = end;
}

void PackedImage::holdRows(uint32_t y0, uint32_t y1) {
    if (!rows_) return;
    y1 = std::min(y1, header_.height);
    y0 = std::min(y0, y1);
    if (y0 < first_row_) throw std::logic_error("PackedImage::holdRows: rows above the held ones were freed");
    if (y0 == first_row_ && y1 <= decoded_rows_) return;
    if (eightBit()) decodeHeldRows(codes8_, y0, y1);
    else decodeHeldRows(codes16_, y0, y1);
}

template <class Code>
void PackedImage::unpackRows(const std::vector<Code>& codes, const PixelRect& rect, float* out) const {
    const uint32_t c = header_.channels;
    const size_t row_samples = size_t(rect.width()) * c;
    for (uint32_t y = rect.y0; y < rect.y1; ++y) {
        assert(y >= first_row_ && y < decoded_rows_);
        const Code* in = codes.data() + (size_t(y - first_row_) * header_.width + rect.x0) * c;
        for (size_t i = 0; i < row_samples; ++i) out[i] = values_[in[i]];
        if (straight_alpha_) premultiply(out, row_samples, c);
        out += row_samples;
    }
}

Image PackedImage::crop(const PixelRect& rect) const {
    if (floats()) return cropOf(header_, rect);
    Image crop = emptyCropOf(header_, rect);
    if (eightBit()) unpackRows(codes8_, rect, crop.pixels.data());
    else unpackRows(codes16_, rect, crop.pixels.data());
    return crop;
}

Image PackedImage::unpack() && {
    if (floats()) return std::move(header_);
    if (rows_) {
        if (first_row_ != 0) throw std::logic_error("PackedImage::unpack: rows were freed");
        holdRows(0, header_.height);
    }
    Image image = header_;
    image.pixels.resize(size_t(image.width) * image.height * image.channels);
    // A band of rows per task: each row's floats are written by one thread.
    parallelFor(image.height, 16, [&](size_t begin, size_t end) {
        const PixelRect rows{0, uint32_t(begin), image.width, uint32_t(end)};
        float* out = image.pixels.data() + begin * image.rowFloats();
        if (eightBit()) unpackRows(codes8_, rows, out);
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
    rows_.reset();
}

size_t PackedImage::bytes() const {
    return codes8_.size() + codes16_.size() * sizeof(uint16_t) + header_.pixels.size() * sizeof(float);
}

}  // namespace ddt
