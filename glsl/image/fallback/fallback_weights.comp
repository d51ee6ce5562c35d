#version 460
#extension GL_GOOGLE_include_directive : require
// The surface's weight at every input pixel, into fallback_weights: the structure tensor smoothed
// along x (fallback_smooth_x.comp) smoothed along y, J, mapped as core's surfaceWeights, with
// T = trace J and the coherence C = ((λ₁ − λ₂) / (λ₁ + λ₂))²:
//     w = kWeightFlat + (kWeightEdge − kWeightFlat) · clamp((log10 T − kLogFlat) / (kLogEdge − kLogFlat), 0, 1)
//                                                 · (s + (1 − s) · C), s the push constant grain_share.
#include "../common.glsl"
#include "fallback.glsl"

void main() {
    const float taps[2 * kFallbackGaussianRadius + 1] = gaussianTaps();
    const uint count = push.width * push.height;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += invocationStride()) {
        const uint x = i % push.width;
        const int64_t y = i / push.width;
        vec3 j = vec3(0.0);  // (xx, yy, xy)
        for (int k = -kFallbackGaussianRadius; k <= kFallbackGaussianRadius; ++k)
            j += taps[k + kFallbackGaussianRadius] *
                 imageLoad(fallback_across, int(clampIndex(y + k, push.height) * push.width + x)).xyz;
        const float energy = j.x + j.y;
        const float log10_energy = log2(energy + 1e-9) / log2(10.0);  // 1e-9: log of a flat region's 0
        const float t = clamp((log10_energy - kFallbackLogFlat) / (kFallbackLogEdge - kFallbackLogFlat), 0.0, 1.0);
        float weight = kFallbackWeightFlat;
        if (t > 0.0) {  // elsewhere the coherence may be 0 / 0
            const float difference = j.x - j.y;
            const float coherence = min((difference * difference + 4.0 * j.z * j.z) / (energy * energy), 1.0);
            const float orientation = push.grain_share + (1.0 - push.grain_share) * coherence;
            weight += (kFallbackWeightEdge - kFallbackWeightFlat) * t * orientation;
        }
        imageStore(fallback_weights, int(i), vec4(weight));
    }
}
