#version 460
#extension GL_GOOGLE_include_directive : require
// Step 1 of an iteration (paper Sec. 3.1): evaluate the flip gain of every edge to test and
// collect the candidates, those whose gain exceeds kFlipGainThreshold. Edges to test: all
// of them in the first iteration (or with the active set off), else the active list that
// the previous flip step built. The candidate count replaces the paper's occlusion query.
#include "common.glsl"

void main() {
    loadParams();
    Control control = params.control;
    const uint iteration = control.iteration;
    const bool from_list = params.active_set != 0 && iteration > 0;
    const uint work = from_list ? control.active_count[iteration & 1] : params.edge_count;
    UintArray active_edges = params.active_list[iteration & 1];

    for (uint i = gl_GlobalInvocationID.x; i < work; i += invocationStride()) {
        const uint e = from_list ? active_edges.at[i] : i;
        const double gain = flipGainOf(e);
        if (gain > kFlipGainThreshold) {
            params.gain.at[e] = gain;
            params.status[0].at[e] = kStatusUndecided;
            params.candidate_list.at[atomicAdd(control.candidate_count, 1)] = e;
        }
    }
}
