// The frame of the reconstruction's per-triangle passes, like render.comp: one invocation per
// edge rasterises the triangles that edge owns (the lowest-id edge of each), within the part
// of the supersampled grid the host gives (first_row, row_count, first_col, col_count; the
// grid is out_width × out_height for the input_width × input_height input). The host sizes
// parts so that no invocation loops more than lavapipe allows (see kItemsPerInvocation).
// The including kernel defines visitTriangle(slot, vertex ids, sample box).
#include "raster.h"  // glsl/, on the include path

// The samples of the part whose positions lie in a triangle's bounding box.
struct SampleBox {
    uint x_lo, x_hi, y_lo, y_hi;  // inclusive; empty when lo > hi
};

SampleBox sampleBoxOf(uvec3 ids) {
    const uint w = push.width;
    const uvec3 xs = ids % w, ys = ids / w;
    const uint in_w = push.input_width, in_h = push.input_height;
    const uint out_w = push.out_width, out_h = push.out_height;
    SampleBox box;
    box.x_lo = max(firstSampleAtOrAfter(min(min(xs.x, xs.y), xs.z), in_w, out_w), push.first_col);
    box.x_hi = min(lastSampleAtOrBefore(max(max(xs.x, xs.y), xs.z), in_w, out_w), push.first_col + push.col_count - 1);
    box.y_lo = max(firstSampleAtOrAfter(min(min(ys.x, ys.y), ys.z), in_h, out_h), push.first_row);
    box.y_hi = min(lastSampleAtOrBefore(max(max(ys.x, ys.y), ys.z), in_h, out_h), push.first_row + push.row_count - 1);
    return box;
}

void visitTriangle(uint slot, uvec3 ids, SampleBox box);

void main() {
    const uint row = push.first_edge_row + gl_GlobalInvocationID.y;
    const uint row_length = 3 * push.width - 2;  // edges per vertex row, the last row has fewer
    const uint e = row * row_length + gl_GlobalInvocationID.x;
    if (row >= push.height || gl_GlobalInvocationID.x >= row_length || e >= push.edge_count) return;
    const uvec4 v = verticesOf(e);
    const uvec4 n = neighboursOf(e);
    if (v.z != kNone && e < n.x && e < n.y) {
        const SampleBox box = sampleBoxOf(v.xyz);
        if (box.x_lo <= box.x_hi && box.y_lo <= box.y_hi) visitTriangle(2 * e, v.xyz, box);
    }
    if (v.w != kNone && e < n.z && e < n.w) {
        const SampleBox box = sampleBoxOf(v.yxw);
        if (box.x_lo <= box.x_hi && box.y_lo <= box.y_hi) visitTriangle(2 * e + 1, v.yxw, box);
    }
}
