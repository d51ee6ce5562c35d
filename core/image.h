// Images in memory; core/io/image_file.h reads and writes them.
//
// Pixels are floats, interleaved, in the file's stored encoding (sRGB-encoded values for
// 8/16-bit files, linear for EXR), scaled to [0, 1] for integer formats. Images with alpha
// are kept premultiplied (associated) in memory, so interpolation gives no dark halos at
// transparent edges; the writer converts back to what the output format stores.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "user_error.h"

namespace ddt {

// The file's sample type; the output is written with the same one where the format allows.
enum class SampleType { UInt8, UInt16, Half, Float };
const char* sampleTypeName(SampleType type);
// "8", "16", "half" or "float" (the --depth values); nullopt for anything else.
std::optional<SampleType> parseSampleType(const std::string& text);

// The largest input read: 16384 × 16384. Larger headers are refused before any allocation.
constexpr uint64_t kMaxInputPixels = uint64_t(1) << 28;

// The path that means standard input to ImageReader and standard output to ImageWriter.
constexpr const char* kStandardStream = "-";
// How messages name `path`: "standard input" / "standard output" for "-", else the path.
std::string inputName(const std::string& path);
std::string outputName(const std::string& path);

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

// Multiplies colour by alpha (the last of `channels`) in place, over `count` samples.
void premultiply(float* pixels, size_t count, uint32_t channels);

}  // namespace ddt
