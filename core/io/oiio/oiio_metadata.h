// ddtup's image attributes to and from OpenImageIO's ImageSpec, for the files that call its
// codecs.
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

}  // namespace ddt
