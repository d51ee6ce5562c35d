// An attribute's value as text, as OpenImageIO 2.4 writes it where a format wants a string of
// any attribute (ParamValue::get_string with no size limit): the IPTC and XMP encoders use it.
#pragma once

#include <string>

#include "image_attributes.h"

namespace ddt {

// A single string as it is; numbers by %d / %u / %g, rationals as n/d, a timecode as
// hh:mm:ss:ff; the values of an element or an array joined by ", ", strings of an array
// quoted with their special characters escaped.
std::string attributeText(const ImageAttribute& attribute);

}  // namespace ddt
