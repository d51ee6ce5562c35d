// An input image held in its file's sample type, made floats only a crop at a time.
//
// The tiles (core/image/tiling.h) read a few hundred rows of the input at a time, but the input
// had been held whole as floats: 160 MB of a 13 MP RGB photograph's 480 MB peak. Held as its
// 8-bit codes it takes a quarter of that, as 16-bit codes half. Half and float inputs are held
// as the floats they already are.
//
// A code becomes the float the decoder gives for it (a table the reader fills from the codec's
// own conversion), then colour is multiplied by alpha when the file stores it straight: the
// operations ImageReader::read did on the whole image, in the same order, so a crop holds the
// very floats a whole-image read would (test/io/test_image_io.cpp checks it).
#pragma once

#include <cstdint>
#include <vector>

#include "image.h"
#include "tiling.h"

namespace ddt {

class PackedImage {
public:
    PackedImage() = default;
    // Held as the floats of `image` (premultiplied, as Image's always are).
    explicit PackedImage(Image image);
    // Held as codes: width × height × channels of them, upright, channels interleaved.
    // `values[code]` is the float a code stands for (256 or 65536 entries); `straight_alpha`:
    // colour is to be multiplied by alpha (the last channel) after the table.
    PackedImage(Image header, std::vector<uint8_t> codes, std::vector<float> values, bool straight_alpha);
    PackedImage(Image header, std::vector<uint16_t> codes, std::vector<float> values, bool straight_alpha);

    // The size, channels, sample type and metadata; its pixels are empty unless held as floats.
    const Image& header() const { return header_; }
    // The whole image when it is held as floats (no copy needed), else null.
    const Image* floats() const { return codes8_.empty() && codes16_.empty() ? &header_ : nullptr; }
    // The pixels inside `rect` as an image of their own.
    Image crop(const PixelRect& rect) const;
    // The whole image as floats; the codes are freed.
    Image unpack() &&;
    // Frees the pixels; the header stays.
    void release();
    // Bytes held for the pixels.
    size_t bytes() const;

private:
    template <class Code>
    void unpackRows(const std::vector<Code>& codes, const PixelRect& rect, float* out) const;

    Image header_;
    std::vector<uint8_t> codes8_;
    std::vector<uint16_t> codes16_;
    std::vector<float> values_;
    bool straight_alpha_ = false;
};

}  // namespace ddt
