// A JPEG file's attributes as OpenImageIO 2.4's JPEG reader makes them from libjpeg's header
// (the markers it keeps: APP0 to APP15 and COM): the same names, types, values and order.
#pragma once

#include <cstdio>  // jpeglib.h needs FILE and size_t declared before it
#include <jpeglib.h>

#include <optional>

#include "exif_decoding.h"
#include "image_attributes.h"

namespace ddt {

// The markers libjpeg must keep for it, before jpeg_read_header.
void keepMetadataMarkers(j_decompress_ptr info);

// For a grey, YCbCr or RGB file whose header is read; nullopt for a file with XMP or IPTC,
// which only OpenImageIO turns into attributes today.
std::optional<ImageAttributes> jpegAttributes(const jpeg_decompress_struct& info, const DecodeExif& decode_exif);

}  // namespace ddt
