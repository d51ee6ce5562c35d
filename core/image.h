// Images in memory and on disk. All file I/O goes through OpenImageIO.
//
// Pixels are floats, interleaved, in the file's stored encoding (sRGB-encoded values for
// 8/16-bit files, linear for EXR), scaled to [0, 1] for integer formats. Images with alpha
// are kept premultiplied (associated) in memory, so interpolation gives no dark halos at
// transparent edges; the writer converts back to what the output format stores.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "user_error.h"

namespace ddt {

// The file's sample type; the output is written with the same one where the format allows.
enum class SampleType { UInt8, UInt16, Half, Float };
const char* sampleTypeName(SampleType type);

// What the input file carried beyond pixels (metadata to copy to the output). Opaque here.
struct ImageMetadata;

struct Image {
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t channels = 0;  // 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA
    std::vector<float> pixels;  // width * height * channels, colour premultiplied when hasAlpha()
    SampleType sample_type = SampleType::UInt8;
    std::shared_ptr<const ImageMetadata> metadata;  // null for images made in memory

    bool hasAlpha() const { return channels == 2 || channels == 4; }
    size_t rowFloats() const { return size_t(width) * channels; }
    const float* row(uint32_t y) const { return pixels.data() + y * rowFloats(); }
    float* row(uint32_t y) { return pixels.data() + y * rowFloats(); }
};

// Reads any file OpenImageIO reads. Throws UserError("PATH: reason") for a missing file, a
// non-image, a truncated file, or a channel layout other than the four above.
Image readImage(const std::string& path);

// Writes an image in bands of rows, to a temporary file in the output's folder that is
// renamed over the output only by commit(): a failed or abandoned write leaves nothing.
// The format follows the output's extension; the sample type follows `like` where the
// format can hold it, else the nearest it supports (reported in notes()).
class ImageWriter {
public:
    ImageWriter(const std::string& path, uint32_t width, uint32_t height, const Image& like);
    ~ImageWriter();
    ImageWriter(const ImageWriter&) = delete;
    ImageWriter& operator=(const ImageWriter&) = delete;

    // Rows [y_begin, y_end) in order, `channels` floats per pixel, premultiplied like Image.
    void writeRows(uint32_t y_begin, uint32_t y_end, const float* rows);
    void commit();
    const std::vector<std::string>& notes() const { return notes_; }

private:
    struct State;
    std::unique_ptr<State> state_;
    std::vector<std::string> notes_;
};

// Writes a whole image through ImageWriter.
std::vector<std::string> writeImage(const std::string& path, const Image& image);

}  // namespace ddt
