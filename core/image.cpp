#include "image.h"

namespace ddt {

const char* sampleTypeName(SampleType type) {
    switch (type) {
        case SampleType::UInt8:
            return "8-bit";
        case SampleType::UInt16:
            return "16-bit";
        case SampleType::Half:
            return "half float";
        case SampleType::Float:
            break;
    }
    return "float";
}

std::optional<SampleType> parseSampleType(const std::string& text) {
    if (text == "8") return SampleType::UInt8;
    if (text == "16") return SampleType::UInt16;
    if (text == "half") return SampleType::Half;
    if (text == "float") return SampleType::Float;
    return std::nullopt;
}

void premultiply(float* pixels, size_t count, uint32_t channels) {
    for (size_t i = 0; i < count; i += channels) {
        const float alpha = pixels[i + channels - 1];
        for (uint32_t k = 0; k + 1 < channels; ++k) pixels[i + k] *= alpha;
    }
}

std::string inputName(const std::string& path) { return path == kStandardStream ? "standard input" : path; }
std::string outputName(const std::string& path) { return path == kStandardStream ? "standard output" : path; }

}  // namespace ddt
