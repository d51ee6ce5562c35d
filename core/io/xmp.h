// The XMP packet OpenImageIO 2.4's encode_xmp makes of an image's attributes in its "minimal"
// form, the one its JPEG writer put in an APP1 block.
#pragma once

#include <string>

#include "image_attributes.h"

namespace ddt {

// The packet, "" when no attribute has an XMP property.
std::string encodeXmp(const ImageAttributes& attributes);

}  // namespace ddt
