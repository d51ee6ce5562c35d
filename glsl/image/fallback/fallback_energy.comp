#version 460
#extension GL_GOOGLE_include_directive : require
// The first step of the surface's weights (core's surfaceWeights): at every input pixel the
// gradient's structure tensor (gx², gy², gx gy), g by the Sobel operator / 8 on the colour
// channels' mean, with clamped edges, into fallback_weights, which fallback_weights.comp
// overwrites.
#include "../common.glsl"
#include "fallback.glsl"

// The colour channels' mean at pixel (x, y) of the crop, clamped into it.
float meanAt(int64_t x, int64_t y) {
    const vec4 pixel = imageLoad(pixels, int(clampIndex(y, push.height) * push.width + clampIndex(x, push.width)));
    const uint colours = push.has_alpha != 0 ? push.channels - 1 : push.channels;
    float sum = 0.0;
    for (uint k = 0; k < colours; ++k) sum += pixel[k];
    return sum / float(colours);
}

void main() {
    const uint count = push.width * push.height;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += invocationStride()) {
        const int64_t x = i % push.width, y = i / push.width;
        const float gx = (meanAt(x + 1, y - 1) + 2 * meanAt(x + 1, y) + meanAt(x + 1, y + 1) - meanAt(x - 1, y - 1) -
                          2 * meanAt(x - 1, y) - meanAt(x - 1, y + 1)) / 8.0;
        const float gy = (meanAt(x - 1, y + 1) + 2 * meanAt(x, y + 1) + meanAt(x + 1, y + 1) - meanAt(x - 1, y - 1) -
                          2 * meanAt(x, y - 1) - meanAt(x + 1, y - 1)) / 8.0;
        imageStore(fallback_weights, int(i), vec4(gx * gx, gy * gy, gx * gy, 0.0));
    }
}
