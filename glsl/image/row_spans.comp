#version 460
#extension GL_GOOGLE_include_directive : require
// Before rendering: for each edge row (the edges the initial grid gave to one vertex row),
// the first and last vertex row its triangles touch. Flips move edges only locally, so the
// host can pick, for every output band, the few edge rows whose triangles may cover it.
// Texels: row_spans[2y] = first row (atomic min), row_spans[2y + 1] = last row (atomic max),
// row_spans[2h] = the widest triangle in input columns, which bounds the render loops.
#include "common.glsl"

void main() {
    const uint w = push.width;
    for (uint e = gl_GlobalInvocationID.x; e < push.edge_count; e += invocationStride()) {
        const uvec4 v = verticesOf(e);
        const uvec4 n = neighboursOf(e);
        uint first = kNone, last = 0, widest = 0;
        // Each triangle is owned by the lowest-id edge among its three (as core's listTriangles).
        if (v.z != kNone && e < n.x && e < n.y) {
            first = min(first, min(min(v.x / w, v.y / w), v.z / w));
            last = max(last, max(max(v.x / w, v.y / w), v.z / w));
            widest = max(widest, max(max(v.x % w, v.y % w), v.z % w) - min(min(v.x % w, v.y % w), v.z % w));
        }
        if (v.w != kNone && e < n.z && e < n.w) {
            first = min(first, min(min(v.x / w, v.y / w), v.w / w));
            last = max(last, max(max(v.x / w, v.y / w), v.w / w));
            widest = max(widest, max(max(v.x % w, v.y % w), v.w % w) - min(min(v.x % w, v.y % w), v.w % w));
        }
        if (first > last) continue;
        imageAtomicMax(row_spans, int(2 * push.height), widest);
        const uint row = min(e / (3 * w - 2), push.height - 1);
        imageAtomicMin(row_spans, int(2 * row), first);
        imageAtomicMax(row_spans, int(2 * row + 1), last);
    }
}
