// EXIF blocks (a TIFF structure: JPEG's APP1 after "Exif\0\0", PNG's eXIf chunk) to and from
// ddtup's image attributes, by OpenImageIO 2.4's rules (its decode_exif and encode_exif), so
// that files read and written without OpenImageIO keep the metadata they kept with it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "image_attributes.h"

namespace ddt {

// Adds the attributes of an EXIF block (with or without the "Exif\0\0" prefix), little- or
// big-endian, to `attributes`: those of the first directory, the EXIF, GPS and
// interoperability directories it points to; a tag whose attribute is already there is passed
// over. Reads nothing outside the block: entries and values out of it are passed over, as
// OpenImageIO passes them over. Returns false where the header or the first directory is
// damaged (adding nothing), or where a Canon maker note read last is (keeping what was read). Of maker notes, Canon's is read ("Canon:" attributes), as
// OpenImageIO reads it; others are not, by either.
bool decodeExif(const uint8_t* data, size_t size, ImageAttributes& attributes);

// The EXIF and GPS attributes, and the TIFF tags EXIF carries (resolution, date, camera, …), as
// a little-endian TIFF structure for PNG's eXIf chunk or JPEG's APP1; "" when no attribute's
// name starts with "Exif:" or "GPS:"; with Canon's maker note from "Canon:" attributes when
// the make is Canon.
std::string encodeExif(const ImageAttributes& attributes);

}  // namespace ddt
