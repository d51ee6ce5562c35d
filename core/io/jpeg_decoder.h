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
    // The same for a JPEG file's bytes in memory.
    JpegDecoder(std::vector<uint8_t> bytes, const std::string& name);
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
    // The next `count` rows the same way, for a caller that takes them as it needs them: the
    // first call starts decoding, the one that reaches the last row ends it (and checks the
    // rest of the file). The rows decoded so far and `count` stay within height().
    void decodeRows(uint32_t count, uint8_t* codes);

    // Decodes the whole file a row at a time, keeping nothing: throws the UserError decode()
    // would. For a caller that decodes the rows later, as it needs them, and must fail before
    // it begins. (jpeg_skip_scanlines, which would save the inverse DCT, does not see a file
    // cut short.) Instead of decoding this one.
    void check();
    // Whether the file is progressive (several scans): libjpeg then holds every coefficient
    // of the image while it decodes, 2 bytes each, more than the codes themselves.
    bool progressive() const;
    // A decoder of the same coefficients stored sequentially (one scan, its Huffman tables
    // fitted), in memory: it decodes to the same codes (the IDCT, upsampling and colour
    // conversion see the same input), a row at a time without the whole image's coefficients.
    // Reads the whole file once, holding its coefficients meanwhile. Throws UserError as
    // decode() does. Instead of decoding this one.
    std::unique_ptr<JpegDecoder> sequential();

    // The attributes OpenImageIO's reader gives (jpeg_header.h); nullopt where it alone can.
    std::optional<ImageAttributes> attributes(const DecodeExif& decode_exif) const;

    // The EXIF block (the APP1 payload after "Exif\0\0", a TIFF header first), or empty.
    const std::vector<uint8_t>& exif() const { return exif_; }
    // The ICC profile (the APP2 "ICC_PROFILE" chunks joined in their order), or empty.
    const std::vector<uint8_t>& iccProfile() const { return icc_; }

private:
    // Reads the header and the metadata markers from the file or the bytes that State holds.
    void readHeader();

    struct State;
    std::unique_ptr<State> state_;
    std::vector<uint8_t> exif_, icc_;
};

}  // namespace ddt
