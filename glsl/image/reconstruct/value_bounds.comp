#version 460
#extension GL_GOOGLE_include_directive : require
// Once per reconstruction: the range each vertex value must stay in, as core's boundsOf: its
// 3 × 3 input neighbourhood's, within [0, 1] for integer sample types.
#include "../common.glsl"
#include "surface.glsl"

void main() {
    const uint w = push.width, h = push.height;
    for (uint i = gl_GlobalInvocationID.x; i < w * h; i += invocationStride()) {
        const uint x = i % w, y = i / w;
        vec4 lo = vec4(uintBitsToFloat(0x7f800000u)), hi = -lo;  // +∞, −∞
        for (uint ny = y > 0 ? y - 1 : 0; ny <= min(h - 1, y + 1); ++ny)
            for (uint nx = x > 0 ? x - 1 : 0; nx <= min(w - 1, x + 1); ++nx) {
                const vec4 value = imageLoad(pixels, int(ny * w + nx));
                lo = min(lo, value);
                hi = max(hi, value);
            }
        if (push.integer_samples != 0) {
            lo = max(lo, vec4(0));
            hi = min(hi, vec4(1));
        }
        imageStore(value_low, int(i), lo);
        imageStore(value_high, int(i), hi);
    }
}
