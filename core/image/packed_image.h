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
//
// Codes may also come from a RowDecoder (row_decoder.h) as the tiles reach them: the image
// then holds only the rows holdRows asks for, a strip of tiles' crops rather than the whole.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "image.h"
#include "row_decoder.h"
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
    // Codes decoded by `rows` as holdRows asks for them; `values` as above, its size (256 or
    // 65536) the codes' bits.
    PackedImage(Image header, std::unique_ptr<RowDecoder> rows, std::vector<float> values, bool straight_alpha);

    // The size, channels, sample type and metadata; its pixels are empty unless held as floats.
    const Image& header() const { return header_; }
    // The whole image when it is held as floats (no copy needed), else null.
    const Image* floats() const { return codes8_.empty() && codes16_.empty() && !rows_ ? &header_ : nullptr; }
    // Rows [y0, y1) held for crop, and the rows above y0 freed where the codes come from a
    // RowDecoder, which decodes on to y1. Later calls may not go back above y0 there. Nothing
    // to do for an image held whole. Throws InputError for a truncated or corrupt file.
    void holdRows(uint32_t y0, uint32_t y1);
    // The pixels inside `rect` as an image of their own; its rows must be held.
    Image crop(const PixelRect& rect) const;
    // The whole image as floats; the codes are freed. From a RowDecoder, only before any row
    // was freed.
    Image unpack() &&;
    // Frees the pixels; the header stays.
    void release();
    // Bytes held for the pixels.
    size_t bytes() const;

private:
    bool eightBit() const { return values_.size() == 256; }
    template <class Code>
    void unpackRows(const std::vector<Code>& codes, const PixelRect& rect, float* out) const;
    template <class Code>
    void decodeHeldRows(std::vector<Code>& codes, uint32_t y0, uint32_t y1);

    Image header_;
    std::vector<uint8_t> codes8_;
    std::vector<uint16_t> codes16_;
    std::vector<float> values_;
    bool straight_alpha_ = false;
    // From a RowDecoder: the codes are rows [first_row_, decoded_rows_); else rows [0, height).
    std::unique_ptr<RowDecoder> rows_;
    uint32_t first_row_ = 0, decoded_rows_ = 0;
};

}  // namespace ddt
