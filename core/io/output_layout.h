// How the premultiplied rows ImageWriter is given become the rows a file stores: alpha kept
// straight or premultiplied, flattened where the format has none, grey widened to RGB where it
// holds no grey.
#pragma once

#include <cstdint>

namespace ddt {

struct OutputLayout {
    uint32_t in_channels = 0;
    uint32_t out_channels = 0;
    bool in_alpha = false;
    bool out_alpha = false;
    bool straight = false;  // divide colour by alpha
    bool flatten = false;   // composite onto white, drop alpha
    bool grey_to_rgb = false;
};

inline bool needsConversion(const OutputLayout& layout) { return layout.straight || layout.flatten || layout.grey_to_rgb; }

inline void expandGreyToRgb(OutputLayout& layout) {
    layout.grey_to_rgb = true;
    layout.out_channels += 2;
}

}  // namespace ddt
