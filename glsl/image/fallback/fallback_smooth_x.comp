#version 460
#extension GL_GOOGLE_include_directive : require
// The structure tensor (fallback_energy.comp) smoothed along x by the Gaussian of σ = 1, with
// clamped edges, into fallback_across: the first of the Gaussian's two separable passes.
#include "../common.glsl"
#include "fallback.glsl"

void main() {
    const float taps[2 * kFallbackGaussianRadius + 1] = gaussianTaps();
    const uint count = push.width * push.height;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += invocationStride()) {
        const int64_t x = i % push.width;
        const uint row = i - uint(x);
        vec3 sum = vec3(0.0);
        for (int k = -kFallbackGaussianRadius; k <= kFallbackGaussianRadius; ++k)
            sum += taps[k + kFallbackGaussianRadius] *
                   imageLoad(fallback_weights, int(row + clampIndex(x + k, push.width))).xyz;
        imageStore(fallback_across, int(i), vec4(sum, 0.0));
    }
}
