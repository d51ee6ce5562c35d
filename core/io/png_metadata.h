// The metadata chunks of the PNG files ImageWriter writes, made from the output's
// OpenImageIO spec (the input's attributes that copyMetadata kept). They are the chunks
// OpenImageIO 2.4's PNG writer wrote from the same spec, in libpng's order, with the same
// contents (read from its source, png_pvt.h, and checked chunk by chunk in
// test/io/test_png_encoder.cpp): gAMA, sRGB and cHRM from the colour space, iCCP, oFFs, pHYs from
// the resolution, tIME from DateTime, and a tEXt chunk for every other string attribute. Where
// libpng refused the spec and OpenImageIO then wrote no file at all (an ICC profile that is
// not one, or one for the wrong colour model; a gamma or a text key libpng cannot store),
// that piece is left out instead. One addition: an eXIf chunk with the EXIF attributes
// (encoded by OpenImageIO, as its later versions do for PNG), which 2.4 kept only as text.
#pragma once

#include <OpenImageIO/imageio.h>

#include <string>
#include <vector>

#include "png_encoder.h"

namespace ddt {

struct PngMetadata {
    std::vector<PngChunk> chunks;     // in the order they go before the image data
    std::vector<std::string> left_out;  // what could not be stored, for notes ("the ICC profile (…)")
};

// `spec.nchannels` says the colour model the ICC profile must match.
PngMetadata pngMetadata(const OIIO::ImageSpec& spec);

}  // namespace ddt
