// How the PNG and JPEG header readers (png_header.h, jpeg_header.h) have an EXIF block turned
// into attributes: by a function the caller gives, so that OpenImageIO's decoder or ddtup's
// own can do it, at the point of the header where OpenImageIO 2.4's readers decode it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

#include "image_attributes.h"

namespace ddt {

// Adds what the EXIF block (a TIFF header first, or "Exif\0\0" and then one) holds to
// `attributes` as OpenImageIO's decode_exif adds to a spec: in place where a name is there.
using DecodeExif = std::function<void(const uint8_t* block, size_t size, ImageAttributes& attributes)>;

}  // namespace ddt
