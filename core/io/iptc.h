// The IPTC-IIM records (record 2, "application") OpenImageIO 2.4's encode_iptc_iim makes of an
// image's attributes: what a JPEG's APP13 "Photoshop 3.0" block holds.
#pragma once

#include <string>

#include "image_attributes.h"

namespace ddt {

// The records in IIM dataset order, "" when no attribute has one.
std::string encodeIptc(const ImageAttributes& attributes);

}  // namespace ddt
