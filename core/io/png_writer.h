// PNG output for ImageWriter: float rows become the 8- or 16-bit samples OpenImageIO's writer
// made of them (its own conversion), which PngEncoder filters and deflates in parallel, after
// the metadata chunks of png_metadata.h.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "png_encoder.h"
#include "png_metadata.h"

namespace ddt {

class PngWriter {
public:
    // `format`: the size, 1 to 4 channels (grey, grey + alpha, RGB, RGBA), 8 or 16 bits; the
    // metadata's channels are the format's. The signature and metadata go to `sink` at once.
    PngWriter(const PngFormat& format, const PngMetadataSource& metadata, PngEncoder::Sink sink);
    ~PngWriter();
    PngWriter(const PngWriter&) = delete;
    PngWriter& operator=(const PngWriter&) = delete;

    // The next `count` rows, format.channels floats a pixel (straight alpha), 0 to 1.
    void writeRows(const float* rows, uint32_t count);
    // The same rows as the codes writeRows makes of them (quantiseRow), at the format's depth.
    void writeCodes(const uint8_t* codes, uint32_t count);
    void writeCodes(const uint16_t* codes, uint32_t count);
    // After the last row.
    void finish();
    // The metadata that could not be stored, for notes ("the ICC profile (…)").
    const std::vector<std::string>& leftOut() const { return left_out_; }
    uint32_t bitDepth() const { return uint32_t(sample_bytes_ * 8); }

private:
    size_t sample_bytes_ = 0;
    size_t row_floats_ = 0;
    std::unique_ptr<PngEncoder> encoder_;
    std::vector<uint8_t> samples_;
    std::vector<std::string> left_out_;
};

}  // namespace ddt
