#version 460
#extension GL_GOOGLE_include_directive : require
// Per edge: the projection onto its bubble, the sums of its two half-edges (a hull edge's
// missing side stays zero). push.step 0 stores it as the bubble's SART weight; 1 applies
// the step b += ω·Σ / weight where the weight is positive (as core).
#include "../common.glsl"
#include "surface.glsl"

void main() {
    for (uint e = gl_GlobalInvocationID.x; e < push.edge_count; e += invocationStride()) {
        const vec4 sum = imageLoad(half_edge_bubble_sums, int(2 * e)) + imageLoad(half_edge_bubble_sums, int(2 * e + 1));
        if (push.step == 0) {
            imageStore(bubble_weights, int(e), sum);
            continue;
        }
        const vec4 weight = imageLoad(bubble_weights, int(e));
        vec4 bubble = imageLoad(bubbles, int(e));
        for (int k = 0; k < 4; ++k)
            if (weight[k] > 0) bubble[k] += kSartRelaxation * sum[k] / weight[k];
        imageStore(bubbles, int(e), bubble);
    }
}
