#version 460
#extension GL_GOOGLE_include_directive : require
// Blends a rendered band (render.comp) towards the Lanczos3 convolution of the input, as
// core's ConvolutionFallback::blend: each sample becomes w · surface + (1 − w) · Lanczos3(input),
// w taken bilinearly from fallback_weights at the sample's input position, then kept to
// [0, 1] for integer sample types and colour within alpha, as the surface is.
#include "../common.glsl"
#include "../reconstruct/surface.glsl"
#include "fallback.glsl"

float weightAt(uint x, uint y) { return imageLoad(fallback_weights, int(y * push.width + x)).x; }

// The surface's weight at the sample of column taps `col` and row taps `row`.
float surfaceWeightAt(LanczosTaps col, LanczosTaps row) {
    const uint right = min(col.cell + 1, push.width - 1), below = min(row.cell + 1, push.height - 1);
    const float top_left = weightAt(col.cell, row.cell), bottom_left = weightAt(col.cell, below);
    const float top = top_left + col.fraction * (weightAt(right, row.cell) - top_left);
    const float bottom = bottom_left + col.fraction * (weightAt(right, below) - bottom_left);
    return top + row.fraction * (bottom - top);
}

void main() {
    const uint count = push.row_count * push.band_width;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += invocationStride()) {
        const uint x = push.band_first_col + i % push.band_width, y = push.first_row + i / push.band_width;
        const LanczosTaps col = tapsAt(x, push.out_width, push.input_width, push.crop_x, push.width);
        const LanczosTaps row = tapsAt(y, push.out_height, push.input_height, push.crop_y, push.height);
        // Along x within each of the six rows, then along y: core's order of sums.
        vec4 convolved = vec4(0);
        for (int j = 0; j < kFallbackTaps; ++j) {
            const uint source = row.index[j] * push.width;
            vec4 across = vec4(0);
            for (int k = 0; k < kFallbackTaps; ++k) across += col.weight[k] * imageLoad(pixels, int(source + col.index[k]));
            convolved += row.weight[j] * across;
        }
        const float w = surfaceWeightAt(col, row);
        vec4 value = w * imageLoad(band, int(i)) + (1.0 - w) * convolved;
        if (push.integer_samples != 0) value = clamp(value, 0.0, 1.0);
        imageStore(band, int(i), colourAtMostAlpha(value));
    }
}
