#include "synthetic_image.h"

#include <algorithm>
#include <cmath>

namespace ddt {

namespace {

constexpr uint32_t kCell = 96;

// Mixes two coordinates into 32 well-spread bits (multiply and xor-shift rounds).
uint32_t mix(uint32_t a, uint32_t b) {
    uint32_t h = a * 0x9e3779b1u ^ (b + 0x7f4a7c15u) * 0x85ebca77u;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

// A value in [−1, 1] from bits.
float signedUnit(uint32_t bits) { return float(bits & 0xffffu) / 32767.5f - 1.0f; }

}  // namespace

Image syntheticImage(uint32_t width, uint32_t height) {
    Image image;
    image.width = width;
    image.height = height;
    image.channels = 3;
    image.sample_type = SampleType::UInt8;
    image.pixels.resize(size_t(width) * height * 3);
    const float u_scale = 1.0f / float(std::max(width, 2u) - 1), v_scale = 1.0f / float(std::max(height, 2u) - 1);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            const float u = float(x) * u_scale, v = float(y) * v_scale;
            float rgb[3] = {0.15f + 0.6f * u, 0.15f + 0.6f * v, 0.45f + 0.3f * (u - v)};

            const uint32_t cell = mix(x / kCell + 0x10000u, y / kCell);  // + 0x10000: not a pixel's hash
            const int32_t dx = int32_t(x % kCell) - int32_t(kCell / 2), dy = int32_t(y % kCell) - int32_t(kCell / 2);
            const int32_t radius = 12 + int32_t((cell >> 2) % 24);
            if (dx * dx + dy * dy <= radius * radius)
                for (uint32_t k = 0; k < 3; ++k) rgb[k] = float((cell >> (8 + 8 * k)) & 0xffu) / 255.0f;
            if ((x + 2 * y) % 128 < 3)
                for (float& value : rgb) value = 0.08f;
            if ((cell & 0x3u) == 0)
                for (float& value : rgb) value += ((x / 4 + y / 4) % 2 ? 0.08f : -0.08f);

            const uint32_t noise = mix(x, y);
            for (uint32_t k = 0; k < 3; ++k) {
                const float value = std::clamp(rgb[k] + 0.02f * signedUnit(noise >> (8 * k)), 0.0f, 1.0f);
                image.pixels[(size_t(y) * width + x) * 3 + k] = std::round(value * 255.0f) / 255.0f;
            }
        }
    }
    return image;
}

}  // namespace ddt
