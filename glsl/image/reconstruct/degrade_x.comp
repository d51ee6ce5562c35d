#version 460
#extension GL_GOOGLE_include_directive : require
// D along x, then the residual: residual[y][x] = input[y][x] − Σ_t tap_x(t) · between_axes[y][3x + 1 + t],
// counted only beyond the quantisation tolerance, as core's beyondTolerance.
#include "../common.glsl"
#include "surface.glsl"
#include "degradation.glsl"

void main() {
    const uint count = push.width * push.height, sub_w = supersampledWidth();
    const int radius = int(push.taps_x_radius);
    for (uint i = gl_GlobalInvocationID.x; i < count; i += invocationStride()) {
        const uint x = i % push.width, y = i / push.width;
        vec4 sum = vec4(0);
        for (int t = -radius; t <= radius; ++t)
            sum += tapX(t) * imageLoad(between_axes, int(y * sub_w) + tapSample(int(x), t, sub_w));
        const vec4 difference = imageLoad(pixels, int(i)) - sum;
        const vec4 beyond = max(abs(difference) - push.quantisation_tolerance, vec4(0));
        imageStore(residual, int(i), sign(difference) * beyond);
    }
}
