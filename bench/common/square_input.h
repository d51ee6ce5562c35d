// Square benchmark inputs of any size from one image: the centred size × size crop, or, when
// size exceeds a side, the image mirrored across its edges (2× = the image 2 × 2, reflected),
// so that texture continues without seams.
#pragma once

#include <cstdint>

#include "image.h"

namespace ddt {

Image squareInput(const Image& image, uint32_t size);

}  // namespace ddt
