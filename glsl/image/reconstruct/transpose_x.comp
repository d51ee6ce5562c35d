#version 460
#extension GL_GOOGLE_include_directive : require
// Dᵀ along x, as a gather: between_axes[y][X] = Σ tap_x(t) · residual[y][x] over the pixels x
// and taps t that read supersample column X.
#include "../common.glsl"
#include "surface.glsl"
#include "degradation.glsl"

void main() {
    const uint sub_w = supersampledWidth(), count = sub_w * push.height;
    const int radius = int(push.taps_x_radius);
    for (uint i = gl_GlobalInvocationID.x; i < count; i += invocationStride()) {
        const int s = int(i % sub_w);
        const uint y = i / sub_w;
        vec4 sum = vec4(0);
        for (int x = firstPixelReading(s, radius); x <= lastPixelReading(s, radius, push.width); ++x) {
            const TapRange range = tapsReading(s, x, radius, push.width);
            for (int t = range.t_lo; t <= range.t_hi; ++t)
                sum += tapX(t) * imageLoad(residual, int(y * push.width) + x);
        }
        imageStore(between_axes, int(i), sum);
    }
}
