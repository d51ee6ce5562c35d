#version 460
#extension GL_GOOGLE_include_directive : require
// Step 1 of an iteration (paper Sec. 3.1): evaluate the flip gain of every edge to test and
// collect the candidates, those whose gain exceeds kFlipGainThreshold. Edges to test: all
// of them in the first iteration (or with the active set off), else the active list that
// the previous flip step built, where candidates whose stencil no flip changed come marked
// kept: they stay candidates with their stored gain, not evaluated again. The candidate count
// replaces the paper's occlusion query.
#include "common.glsl"

void main() {
    const uint iteration = control.iteration;
    const bool from_list = push.active_set != 0 && iteration > 0;
    const uint work = from_list ? control.active_count[iteration & 1] : push.edge_count;
    for (uint i = gl_GlobalInvocationID.x; i < work; i += invocationStride()) {
        uint e = i;
        if (from_list) e = (iteration & 1) == 0 ? imageLoad(active_list0, int(i)).x : imageLoad(active_list1, int(i)).x;
        // A kept candidate (flip.comp) has its gain, unchanged, stored already.
        const bool kept = from_list && imageLoad(marks, int(e)).x == keptMark(iteration);
        const double gain = kept ? 0.0lf : flipGainOf(e);
        if (kept || gain > kFlipGainThreshold) {
            if (!kept) setGain(e, gain);
            setStatus(0, e, kStatusUndecided);
            imageStore(candidate_list, int(atomicAdd(control.candidate_count, 1)), uvec4(e));
        }
    }
}
