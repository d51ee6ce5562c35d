// Decoding JPEG files with libjpeg-turbo itself, the library OpenImageIO's JPEG reader calls, with
// the same settings (its defaults: the accurate integer IDCT, smooth chroma upsampling), so the
// codes are the ones OpenImageIO gives. A step towards reading photographs without
// OpenImageIO in the process (its libraries hold most of a small job's memory). Grey, YCbCr
// and RGB files; CMYK and YCCK ones (which OpenImageIO converts to RGB its own way) are not
// taken: `decodable()` says so before anything is decoded.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "exif_decoding.h"
#include "image_attributes.h"

namespace ddt {

class JpegDecoder {
public:
    // Reads the file's header and the markers kept for metadata. Throws UserError("NAME: …")
    // for a file that is not a readable JPEG; `name` is how messages call the file.
    JpegDecoder(const std::string& path, const std::string& name);
    ~JpegDecoder();
    JpegDecoder(const JpegDecoder&) = delete;
    JpegDecoder& operator=(const JpegDecoder&) = delete;

    uint32_t width() const;
    uint32_t height() const;
    uint32_t channels() const;  // 1 (grey) or 3 (RGB) once decodable
    // Whether the colour model is grey, YCbCr or RGB.
    bool decodable() const;

    // Every row, top to bottom, channels interleaved: width · height · channels codes, as
    // stored (not turned by any EXIF orientation). Throws UserError for a truncated or corrupt
    // file: libjpeg's warnings (it fills what is missing with grey) count as errors. Once.
    void decode(uint8_t* codes);

    // The attributes OpenImageIO's reader gives (jpeg_header.h); nullopt where it alone can.
    std::optional<ImageAttributes> attributes(const DecodeExif& decode_exif) const;

    // The EXIF block (the APP1 payload after "Exif\0\0", a TIFF header first), or empty.
    const std::vector<uint8_t>& exif() const { return exif_; }
    // The ICC profile (the APP2 "ICC_PROFILE" chunks joined in their order), or empty.
    const std::vector<uint8_t>& iccProfile() const { return icc_; }

private:
    struct State;
    std::unique_ptr<State> state_;
    std::vector<uint8_t> exif_, icc_;
};

}  // namespace ddt
