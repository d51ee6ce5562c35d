// JPEG output for ImageWriter with libjpeg-turbo itself, set up as OpenImageIO 2.4's JPEG writer
// (jpegoutput.cpp) set it up for the images ddtup writes, so that the files are byte-identical to
// the ones it wrote: grey or RGB, 8 bits, its quality and chroma subsampling ("jpeg:subsampling",
// else libjpeg's 4:2:0), the JFIF density from the resolution, and its markers in its order:
// COM from ImageDescription, APP1 EXIF, APP13 IPTC, APP1 XMP, APP2 ICC profile chunks. Float
// rows become the codes OpenImageIO's conversion made of them (sample_quantise.h). One
// difference, a fix: a profile of several chunks is stored whole (OpenImageIO's last chunk
// held the wrong bytes).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "image_attributes.h"

namespace ddt {

struct JpegFormat {
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t channels = 0;  // 1 grey, 3 RGB
    int quality = 95;       // 1 to 100, libjpeg's scale
};

// What the markers are made of. The EXIF, IPTC and XMP encodings come from the caller (exif.h's
// encodeExifBlock, iptc.h's encodeIptc, xmp.h's encodeXmp), made of
// jpegAttributes(), as the writer made them.
struct JpegMetadata {
    ImageAttributes attributes;  // jpegAttributes() of the output's
    std::string exif;            // the TIFF structure of the APP1 EXIF marker, written always
    std::string iptc;            // IPTC-IIM records for the APP13 marker, or ""
    std::string xmp;             // the XMP packet for the second APP1 marker, or ""
};

// The attributes as OpenImageIO's JPEG writer encoded them: EXIF's copy of the resolution
// dropped (the JFIF density holds it) and "Exif:ColorSpace" 1 for an sRGB image.
ImageAttributes jpegAttributes(const ImageAttributes& attributes);

class JpegWriter {
public:
    // Receives the file's bytes in order. It may throw to stop the writer (a full disk); the
    // exception comes out of the call that was writing, once, and the writer is done.
    using Sink = std::function<void(const uint8_t* data, size_t size)>;

    // Writes the header and the markers to `sink`. Throws std::invalid_argument for a format
    // JPEG cannot hold.
    JpegWriter(const JpegFormat& format, const JpegMetadata& metadata, Sink sink);
    ~JpegWriter();
    JpegWriter(const JpegWriter&) = delete;
    JpegWriter& operator=(const JpegWriter&) = delete;

    // The next `count` rows, format.channels floats a pixel, 0 to 1.
    void writeRows(const float* rows, uint32_t count);
    // The same rows as the 8-bit codes writeRows makes of them (quantiseRow).
    void writeCodes(const uint8_t* codes, uint32_t count);
    // After the last row.
    void finish();
    // The metadata that could not be stored, for notes ("the ICC profile (…)").
    const std::vector<std::string>& leftOut() const { return left_out_; }

private:
    struct State;
    std::unique_ptr<State> state_;
    std::vector<std::string> left_out_;
};

}  // namespace ddt
