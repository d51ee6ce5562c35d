#version 460
#extension GL_GOOGLE_include_directive : require
// Once per reconstruction: every edge's starting bubble, as core's initialSurface: the
// midpoint of a cubic along the edge's line through y(2p − q), y(p), y(q), y(2q − p) (points
// clamped into the image), minus the linear midpoint.
#include "../common.glsl"
#include "surface.glsl"

vec4 inputAt(int x, int y) {
    return imageLoad(pixels, clamp(y, 0, int(push.height) - 1) * int(push.width) + clamp(x, 0, int(push.width) - 1));
}

void main() {
    const int w = int(push.width);
    for (uint e = gl_GlobalInvocationID.x; e < push.edge_count; e += invocationStride()) {
        const uvec4 v = verticesOf(e);
        const int px = int(v.x) % w, py = int(v.x) / w, qx = int(v.y) % w, qy = int(v.y) / w;
        const vec4 p = inputAt(px, py), q = inputAt(qx, qy);
        const vec4 before = inputAt(2 * px - qx, 2 * py - qy), after = inputAt(2 * qx - px, 2 * qy - py);
        imageStore(bubbles, int(e), (-before + 9 * p + 9 * q - after) / 16 - (p + q) / 2);
    }
}
