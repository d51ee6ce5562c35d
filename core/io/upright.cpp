#include "upright.h"

#include <cstring>
#include <vector>

namespace ddt {

bool swapsSides(int orientation) { return orientation >= 5 && orientation <= 8; }

void makeUpright(void* samples, size_t pixel_bytes, uint32_t stored_width, uint32_t stored_height, int orientation) {
    if (orientation < 2 || orientation > 8) return;
    const size_t w = stored_width, h = stored_height;
    const bool swapped = swapsSides(orientation);
    const size_t upright_width = swapped ? h : w, upright_height = swapped ? w : h;
    auto* pixels = static_cast<uint8_t*>(samples);
    const std::vector<uint8_t> stored(pixels, pixels + w * h * pixel_bytes);
    for (size_t y = 0; y < upright_height; ++y)
        for (size_t x = 0; x < upright_width; ++x) {
            // The stored pixel (sx, sy) that lands at the upright (x, y).
            size_t sx = x, sy = y;
            switch (orientation) {
                case 2: sx = w - 1 - x; break;                   // mirrored left to right
                case 3: sx = w - 1 - x; sy = h - 1 - y; break;   // half a turn
                case 4: sy = h - 1 - y; break;                   // mirrored top to bottom
                case 5: sx = y; sy = x; break;                   // mirrored across the main diagonal
                case 6: sx = y; sy = h - 1 - x; break;           // a quarter turn clockwise
                case 7: sx = w - 1 - y; sy = h - 1 - x; break;   // mirrored across the other diagonal
                case 8: sx = w - 1 - y; sy = x; break;           // a quarter turn anticlockwise
            }
            std::memcpy(pixels + (y * upright_width + x) * pixel_bytes, &stored[(sy * w + sx) * pixel_bytes], pixel_bytes);
        }
}

}  // namespace ddt
