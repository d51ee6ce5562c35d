#version 460
#extension GL_GOOGLE_include_directive : require
// Step 3 (paper Sec. 3.3): flip every accepted candidate and patch its neighbours' records.
//
// Why one thread per accepted edge may write its neighbours without locks: the selection
// guarantees that no accepted edge lies in the 2-region of another. A flip of g
// writes only g's closed 1-region (g and its four neighbours). If the closed 1-regions of
// two accepted edges g and h met, h would be a neighbour of g or a neighbour of one of
// g's neighbours, i.e. h would lie in g's 2-region. So the written sets are disjoint, and
// every record a thread reads here is one only that thread writes. The same argument shows
// each accepted gain is exact: a gain reads only the records of the closed 1-region (for
// variance, of e alone).
//
// With the active set on, the thread then lists the edges whose gain its flip may have
// changed — for Sederberg's cost and face-SCF its closed 2-region in the new mesh (their gain
// reads the records of an edge and its neighbours), for variance its closed 1-region (the
// gain reads the edge's own record) — and every candidate that was not flipped, for the next
// iteration, the latter marked kept: unless a flip's ROI also lists it, its stencil and so its
// gain stay, and the candidates step lists it again without evaluating it. Statuses are reset
// to none for the next iteration.
#include "common.glsl"

// After e's flip, neighbour n (whose triangle with e had third vertex old_near) lies in a
// new triangle with third vertex new_near: its slot that held e now holds `successor`, the
// slot that held the other old edge now holds e. As core/image/mesh.cpp patchNeighbour.
void patchNeighbour(uint n, uint e, uint old_near, uint new_near, uint successor) {
    if (n == kNone) return;
    uvec4 v = verticesOf(n);
    uvec4 nb = neighboursOf(n);
    if (v.z == old_near) {
        v.z = new_near;
        nb.x = nb.x == e ? successor : e;
        nb.y = nb.y == e ? successor : e;
    } else {
        v.w = new_near;
        nb.z = nb.z == e ? successor : e;
        nb.w = nb.w == e ? successor : e;
    }
    imageStore(edge_vertices, int(n), v);
    imageStore(edge_neighbours, int(n), nb);
}

// (a, b, l, r) -> (r, l, a, b) and (bl, la, ar, rb) -> (la, ar, rb, bl), as core's flipEdge.
void flipEdge(uint e) {
    const uvec4 v = verticesOf(e);
    const uvec4 n = neighboursOf(e);
    imageStore(edge_vertices, int(e), uvec4(v.w, v.z, v.x, v.y));
    imageStore(edge_neighbours, int(e), uvec4(n.y, n.z, n.w, n.x));
    patchNeighbour(n.x, e, v.x, v.w, n.w);
    patchNeighbour(n.y, e, v.y, v.w, n.z);
    patchNeighbour(n.z, e, v.y, v.z, n.y);
    patchNeighbour(n.w, e, v.x, v.z, n.x);
}

// Puts e in the next iteration's active list once, marked kept or to retest (keptMark).
void activate(uint e, uint iteration, uint mark) {
    if (imageAtomicMax(marks, int(e), mark) < keptMark(iteration)) {
        const int slot = int(atomicAdd(control.active_count[iteration & 1], 1));
        if ((iteration & 1) == 0) imageStore(active_list0, slot, uvec4(e));
        else imageStore(active_list1, slot, uvec4(e));
    }
}

// The closed ROI of e: its closed 2-region, or for variance its closed 1-region. A neighbour's
// neighbours include e and the neighbour of e that shares its triangle, listed here already:
// skipping them saves 8 of the 21 atomic marks (lavapipe runs atomics lane by lane).
void activateClosedRoi(uint e, uint iteration) {
    activate(e, iteration, retestMark(iteration));
    const uvec4 level1 = neighboursOf(e);
    for (int i = 0; i < 4; ++i) {
        if (level1[i] == kNone) continue;
        activate(level1[i], iteration, retestMark(iteration));
        if (kCost == kCostVariance) continue;
        const uvec4 level2 = neighboursOf(level1[i]);
        for (int j = 0; j < 4; ++j)
            if (level2[j] != kNone && level2[j] != e && !any(equal(level1, uvec4(level2[j])))) activate(level2[j], iteration, retestMark(iteration));
    }
}

// Invocation i resets candidate i and flips accepted edge i (select.comp lists them): the
// flips, a fraction of the candidates, run on adjacent invocations, not scattered among
// them. lavapipe runs a branch for a whole SIMD row when one of its lanes takes it, so
// scattered flips cost nearly as much as flipping every candidate.
void main() {
    const uint count = control.candidate_count;
    const uint flips = control.flips_in_iteration;
    const uint final_status = control.round & 1;
    const uint next_iteration = control.iteration;  // the plan step advanced it already

    for (uint i = gl_GlobalInvocationID.x; i < count; i += invocationStride()) {
        const uint e = imageLoad(candidate_list, int(i)).x;
        const uint status = statusOf(final_status, e);
        setStatus(0, e, kStatusNone);
        setStatus(1, e, kStatusNone);
        if (status != kStatusAccepted && push.active_set != 0) activate(e, next_iteration, keptMark(next_iteration));
        if (i < flips) {
            const uint flipped = imageLoad(accepted_list, int(i)).x;
            flipEdge(flipped);
            if (push.active_set != 0) activateClosedRoi(flipped, next_iteration);
        }
    }
}
