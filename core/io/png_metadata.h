// The metadata chunks of the PNG files ImageWriter writes, made from the output's attributes
// (the input's that outputAttributes kept). They are the chunks
// OpenImageIO 2.4's PNG writer wrote from the same spec, in libpng's order, with the same
// contents (read from its source, png_pvt.h, and checked chunk by chunk in
// test/io/test_png_encoder.cpp): gAMA, sRGB and cHRM from the colour space, iCCP, oFFs, pHYs from
// the resolution, tIME from DateTime, and a tEXt chunk for every other string attribute. Where
// libpng refused the spec and OpenImageIO then wrote no file at all (an ICC profile that is
// not one, or one for the wrong colour model; a gamma or a text key libpng cannot store),
// that piece is left out instead. One addition: an eXIf chunk with the EXIF attributes
// (encoded by OpenImageIO, as its later versions do for PNG), which 2.4 kept only as text.
// OpenImageIO's spec was the input; its rules for finding and converting attributes are
// ImageAttributes' (image_attributes.h).
#pragma once

#include <string>
#include <vector>

#include "image_attributes.h"
#include "png_encoder.h"

namespace ddt {

struct PngMetadata {
    std::vector<PngChunk> chunks;     // in the order they go before the image data
    std::vector<std::string> left_out;  // what could not be stored, for notes ("the ICC profile (…)")
};

// What the chunks are made of.
struct PngMetadataSource {
    ImageAttributes attributes;
    uint32_t channels = 0;               // 1 to 4: the colour model the ICC profile must match
    int32_t x_offset = 0, y_offset = 0;  // the oFFs chunk's (OpenImageIO's spec.x, spec.y)
    std::string exif;                    // the eXIf chunk's data (encodeExif in exif.h), or ""
};

PngMetadata pngMetadata(const PngMetadataSource& source);

}  // namespace ddt
