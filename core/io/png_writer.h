// PNG output for ImageWriter: float rows become the 8- or 16-bit samples OpenImageIO's writer
// made of them (its own conversion), which PngEncoder filters and deflates in parallel, after
// the metadata chunks of png_metadata.h.
#pragma once

#include <OpenImageIO/imageio.h>

#include <memory>
#include <string>
#include <vector>

#include "png_encoder.h"

namespace ddt {

class PngWriter {
public:
    // `spec`: the size, 1 to 4 channels (grey, grey + alpha, RGB, RGBA), UINT8 or UINT16
    // samples, and the metadata attributes. The signature and metadata go to `sink` at once.
    PngWriter(const OIIO::ImageSpec& spec, PngEncoder::Sink sink);
    ~PngWriter();
    PngWriter(const PngWriter&) = delete;
    PngWriter& operator=(const PngWriter&) = delete;

    // The next `count` rows, spec.nchannels floats a pixel (straight alpha), 0 to 1.
    void writeRows(const float* rows, uint32_t count);
    // After the last row.
    void finish();
    // The metadata that could not be stored, for notes ("the ICC profile (…)").
    const std::vector<std::string>& leftOut() const { return left_out_; }

private:
    OIIO::TypeDesc type_;
    size_t row_floats_ = 0;
    std::unique_ptr<PngEncoder> encoder_;
    std::vector<uint8_t> samples_;
    std::vector<std::string> left_out_;
};

}  // namespace ddt
