// A PNG file's layout and attributes as OpenImageIO 2.4's PNG reader makes them: the same
// libpng calls up to the image data (so the same chunks are accepted, checked and dropped),
// the same attribute names, types, values and order. Pixels are libspng's (png_decoder.h).
#pragma once

#include <optional>
#include <string>

#include "exif_decoding.h"
#include "image_attributes.h"

namespace ddt {

struct PngHeader {
    uint32_t width = 0, height = 0;
    uint32_t channels = 0;  // 1 to 4, alpha last, palettes and tRNS expanded
    uint32_t bits = 0;      // 8 or 16
    ImageAttributes attributes;
};

// Throws UserError("NAME: not a readable PNG image (PNG read error: …)") as OpenImageIO words
// it, `name` calling the file. nullopt for a file that holds XMP, which only OpenImageIO
// turns into attributes today.
std::optional<PngHeader> readPngHeader(const std::string& path, const std::string& name, const DecodeExif& decode_exif);

}  // namespace ddt
