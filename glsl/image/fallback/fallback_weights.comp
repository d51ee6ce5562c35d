#version 460
#extension GL_GOOGLE_include_directive : require
// The surface's weight at every input pixel, into fallback_weights: the energy smoothed along x
// (fallback_smooth_x.comp) smoothed along y, T, mapped as core's surfaceWeights:
//     w = kWeightFlat + (kWeightEdge − kWeightFlat) · clamp((log10 T − kLogFlat) / (kLogEdge − kLogFlat), 0, 1).
#include "../common.glsl"
#include "fallback.glsl"

void main() {
    const float taps[2 * kFallbackGaussianRadius + 1] = gaussianTaps();
    const uint count = push.width * push.height;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += invocationStride()) {
        const uint x = i % push.width;
        const int64_t y = i / push.width;
        float sum = 0.0;
        for (int k = -kFallbackGaussianRadius; k <= kFallbackGaussianRadius; ++k)
            sum += taps[k + kFallbackGaussianRadius] * imageLoad(fallback_across, int(clampIndex(y + k, push.height) * push.width + x)).x;
        const float log10_energy = log2(sum + 1e-9) / log2(10.0);  // 1e-9: log of a flat region's 0
        const float t = clamp((log10_energy - kFallbackLogFlat) / (kFallbackLogEdge - kFallbackLogFlat), 0.0, 1.0);
        imageStore(fallback_weights, int(i), vec4(kFallbackWeightFlat + (kFallbackWeightEdge - kFallbackWeightFlat) * t));
    }
}
