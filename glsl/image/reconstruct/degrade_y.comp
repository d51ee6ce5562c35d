#version 460
#extension GL_GOOGLE_include_directive : require
// D along y: between_axes[y][X] = Σ_t tap_y(t) · supersamples[3y + 1 + t][X].
#include "../common.glsl"
#include "surface.glsl"
#include "degradation.glsl"

void main() {
    const uint sub_w = supersampledWidth(), count = sub_w * push.height;
    const int radius = int(push.taps_y_radius);
    for (uint i = gl_GlobalInvocationID.x; i < count; i += invocationStride()) {
        const uint x = i % sub_w, y = i / sub_w;
        vec4 sum = vec4(0);
        for (int t = -radius; t <= radius; ++t)
            sum += tapY(t) * imageLoad(supersamples, supersampleAt(x, tapSample(int(y), t, supersampledHeight())));
        imageStore(between_axes, int(i), sum);
    }
}
