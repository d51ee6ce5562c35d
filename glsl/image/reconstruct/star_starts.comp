#version 460
#extension GL_GOOGLE_include_directive : require
// Once per reconstruction: every vertex's lowest-id edge, where update_values starts walking
// its star, so its sums are added in an order fixed by the mesh. The host fills star_start
// with kNone first; integer atomicMin gives the same result in any order.
#include "../common.glsl"
#include "surface.glsl"

void main() {
    for (uint e = gl_GlobalInvocationID.x; e < push.edge_count; e += invocationStride()) {
        const uvec4 v = verticesOf(e);
        imageAtomicMin(star_start, int(v.x), e);
        imageAtomicMin(star_start, int(v.y), e);
    }
}
