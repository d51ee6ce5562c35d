#version 460
#extension GL_GOOGLE_include_directive : require
// The mesh cost (cost-init, cost-final): every workgroup sums the edge shares of the cost
// (kCost, see edgeCostOf) of a fixed, strided set of edges and reduces them in shared memory;
// the host adds the partial sums.
// Fixed assignment and reduction order make the result deterministic. With push.step = 1 it
// also stores every edge's cost in the gain array (tests compare them with core's).
#include "common.glsl"

shared double partial[kGroupSize];

void main() {
    const uint lane = gl_LocalInvocationID.x;
    precise double sum = 0.0lf;
    for (uint e = gl_GlobalInvocationID.x; e < push.edge_count; e += invocationStride()) {
        const double cost = edgeCostOf(e);
        sum += cost;
        if (push.step != 0) setGain(e, cost);
    }
    partial[lane] = sum;
    barrier();
    for (uint width = kGroupSize / 2; width > 0; width /= 2) {
        if (lane < width) partial[lane] += partial[lane + width];
        barrier();
    }
    if (lane == 0) imageStore(partial_sums, int(gl_WorkGroupID.x), uvec4(unpackDouble2x32(partial[0]), 0u, 0u));
}
