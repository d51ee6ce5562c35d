// ddtup's image attributes to and from OpenImageIO's ImageSpec, for the files that call its
// codecs, and what only OpenImageIO makes of them today (the EXIF block).
#pragma once

#include <OpenImageIO/imageio.h>

#include <string>

#include "image_attributes.h"

namespace ddt {

// The spec's extra attributes, in its order. Values of types ddtup does not hold (pointers)
// are left out: no reader makes them.
ImageAttributes attributesOf(const OIIO::ImageSpec& spec);

// Appends `attributes` to the spec's extra attributes, as they are.
void addAttributes(const ImageAttributes& attributes, OIIO::ImageSpec& spec);

// The EXIF and GPS attributes, and the TIFF tags EXIF carries (resolution, date, camera, …),
// encoded as the little-endian TIFF structure of PNG's eXIf chunk; "" when there is no EXIF
// or GPS attribute.
std::string exifBlock(const ImageAttributes& attributes);

// OpenImageIO's decoding of an EXIF block (exif_decoding.h's DecodeExif), until ddtup has its own.
void decodeExifWithOiio(const uint8_t* block, size_t size, ImageAttributes& attributes);

}  // namespace ddt
