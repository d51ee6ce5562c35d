#version 460
#extension GL_GOOGLE_include_directive : require
// Dᵀ along y, as a gather: supersamples[Y][X] = Σ tap_y(t) · between_axes[y][X] over the rows
// y and taps t that read supersample row Y.
#include "../common.glsl"
#include "surface.glsl"
#include "degradation.glsl"

void main() {
    const uint sub_w = supersampledWidth(), count = sub_w * supersampledHeight();
    const int radius = int(push.taps_y_radius);
    for (uint i = gl_GlobalInvocationID.x; i < count; i += invocationStride()) {
        const uint x = i % sub_w;
        const int s = int(i / sub_w);
        vec4 sum = vec4(0);
        for (int y = firstPixelReading(s, radius); y <= lastPixelReading(s, radius, push.height); ++y) {
            const TapRange range = tapsReading(s, y, radius, push.height);
            for (int t = range.t_lo; t <= range.t_hi; ++t)
                sum += tapY(t) * imageLoad(between_axes, int(uint(y) * sub_w + x));
        }
        imageStore(supersamples, int(i), sum);
    }
}
