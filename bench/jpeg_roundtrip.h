// The JPEG protocol's compression: an image stored as a baseline JPEG and read back, as a
// low-resolution picture from the web or a camera would arrive. Through a temporary file,
// with core's writer and reader (the same codec path as ddtup's own JPEG output).
#pragma once

#include "image.h"

namespace bench {

// `image` (grey or RGB) after a JPEG round trip at `quality` (1..100).
ddt::Image jpegRoundTrip(const ddt::Image& image, int quality);

}  // namespace bench
