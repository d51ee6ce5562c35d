// Decoding PNG files with libspng, to the samples OpenImageIO's reader (libpng) gives: grey,
// grey+alpha, RGB or RGBA in 8 or 16 bits; palettes expanded to RGB, grey below 8 bits scaled
// to 8, a tRNS transparency made an alpha channel; no gamma applied. A step towards reading
// images without OpenImageIO in the process, as jpeg_decoder.h.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace ddt {

class PngDecoder {
public:
    // Reads the chunks before the image data. Throws UserError("NAME: …") for a file that is
    // not a readable PNG; `name` is how messages call the file.
    PngDecoder(const std::string& path, const std::string& name);
    ~PngDecoder();
    PngDecoder(const PngDecoder&) = delete;
    PngDecoder& operator=(const PngDecoder&) = delete;

    uint32_t width() const;
    uint32_t height() const;
    uint32_t channels() const;    // 1 to 4, alpha last
    uint32_t sampleBits() const;  // 8 or 16

    // Every row, top to bottom, channels interleaved: width · height · channels samples of
    // sampleBits() (uint8_t or uint16_t in host order). Throws UserError for a truncated or
    // corrupt file. Once.
    void decode(void* samples);
    // Decodes the whole file a row at a time, keeping nothing: throws the UserError decode()
    // would. For a caller that decodes the rows later, as it needs them, and must fail before
    // it begins. Instead of decoding this one; not for an interlaced file.
    void check();
    // Whether the rows are stored in passes (Adam7): decodeRows cannot give them in order.
    bool interlaced() const;
    // The next `count` rows the same way, for a caller that takes them as it needs them (not
    // for an interlaced file): the first call starts decoding, the one that reaches the last
    // row reads on to the file's end and checks it. The rows decoded so far and `count` stay
    // within height().
    void decodeRows(uint32_t count, void* samples);

    // The eXIf chunk (a TIFF header first) and the iCCP profile (uncompressed), or empty.
    std::vector<uint8_t> exif() const;
    std::vector<uint8_t> iccProfile() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace ddt
