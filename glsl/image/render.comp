#version 460
#extension GL_GOOGLE_include_directive : require
// Renders one window (a band of output rows, a range of columns) from the optimised mesh:
// one invocation per edge rasterises the triangles that edge owns (the lowest-id edge of
// each triangle), with the exact coverage tests of raster.h, so each pixel is written by
// exactly one invocation and the result does not depend on timing. Same sampling
// convention as core/image/render.cpp. The dispatch is two-dimensional: y picks an edge row (the
// edges the initial grid gave to one vertex row), x an edge within it. The host sizes the
// window so that no invocation loops more than lavapipe allows (see kItemsPerInvocation).
// The mesh may be a tile's: the crop at (crop_x, crop_y) of the whole input, whose vertices
// are placed at whole-input coordinates so that sampling is the untiled image's.
// With push.quadratic it renders the consistent reconstruction (glsl/image/reconstruct/): the
// reconstructed vertex values plus the edge bubbles, each sample clamped to its triangle's
// vertex range and premultiplied colour to at most alpha, as core's MeshRenderer.
#include "common.glsl"
#include "raster.h"
#include "reconstruct/surface.glsl"

vec4 vertexValue(uint id) { return push.quadratic != 0 ? imageLoad(surface_values, int(id)) : imageLoad(pixels, int(id)); }

// The quadratic surface, clamped as core's MeshRenderer::renderWindow.
vec4 clampedQuadratic(vec3 l, vec4 z[3], vec4 b[3]) {
    vec4 value = quadraticSurface(l, z[0], z[1], z[2], b[0], b[1], b[2]);
    return colourAtMostAlpha(clamp(value, min(min(z[0], z[1]), z[2]), max(max(z[0], z[1]), z[2])));
}

// Triangle `slot` (see reconstruct/surface.glsl) with vertices i0, i1, i2.
void renderTriangle(uint slot, uint i0, uint i1, uint i2) {
    const uint w = push.width;  // the crop's width, which vertex ids count in
    const uint in_w = push.input_width, in_h = push.input_height;
    const uint out_w = push.out_width, out_h = push.out_height;
    const uint ids[3] = uint[3](i0, i1, i2);
    int64_t px[3], py[3];
    vec4 z[3];  // premultiplied vertex values
    vec4 b[3];  // bubbles of the edges opposite them (quadratic only)
    uint x0 = in_w, x1 = 0, y0 = in_h, y1 = 0;
    for (int k = 0; k < 3; ++k) {
        const uint x = ids[k] % w + push.crop_x, y = ids[k] / w + push.crop_y;
        px[k] = vertexCoord(x, out_w);
        py[k] = vertexCoord(y, out_h);
        z[k] = vertexValue(ids[k]);
        x0 = min(x0, x); x1 = max(x1, x);
        y0 = min(y0, y); y1 = max(y1, y);
    }
    if (push.quadratic != 0) {
        const uvec3 edges = slotEdges(slot);
        for (int k = 0; k < 3; ++k) b[k] = imageLoad(bubbles, int(edges[k]));
    }
    const uint band_end = push.first_row + push.row_count;
    const uint x_lo = max(firstSampleAtOrAfter(x0, in_w, out_w), push.first_col);
    const uint x_hi = min(lastSampleAtOrBefore(x1, in_w, out_w), push.first_col + push.col_count - 1);
    const uint y_lo = max(firstSampleAtOrAfter(y0, in_h, out_h), push.first_row);
    const uint y_hi = min(lastSampleAtOrBefore(y1, in_h, out_h), band_end - 1);
    for (uint y = y_lo; y <= y_hi && y_lo <= y_hi; ++y) {
        const int64_t sv = sampleCoord(y, in_h, out_h);
        const int dir_v = sampleDirection(sv, in_h, out_h);
        for (uint x = x_lo; x <= x_hi && x_lo <= x_hi; ++x) {
            const int64_t su = sampleCoord(x, in_w, out_w);
            const int dir_u = sampleDirection(su, in_w, out_w);
            int64_t weight[3];  // edge function opposite each vertex = barycentric weight × 2·area
            bool inside = true;
            for (int k = 0; k < 3; ++k) {
                const int p = (k + 1) % 3, q = (k + 2) % 3;
                inside = inside && sampleSide(px[p], py[p], px[q], py[q], su, sv, dir_u, dir_v) > 0;
                weight[k] = (px[q] - px[p]) * (sv - py[p]) - (py[q] - py[p]) * (su - px[p]);
            }
            if (!inside) continue;
            const float total = float(weight[0] + weight[1] + weight[2]);
            const vec3 lambda = vec3(float(weight[0]), float(weight[1]), float(weight[2])) / total;
            const vec4 value = push.quadratic != 0 ? clampedQuadratic(lambda, z, b)
                                                   : lambda.x * z[0] + lambda.y * z[1] + lambda.z * z[2];
            imageStore(band, int((y - push.first_row) * push.band_width + x - push.band_first_col), value);
        }
    }
}

void main() {
    const uint row = push.first_edge_row + gl_GlobalInvocationID.y;
    const uint row_length = 3 * push.width - 2;  // edges per vertex row, the last row has fewer
    const uint e = row * row_length + gl_GlobalInvocationID.x;
    if (row >= push.height || gl_GlobalInvocationID.x >= row_length || e >= push.edge_count) return;
    const uvec4 v = verticesOf(e);
    const uvec4 n = neighboursOf(e);
    if (v.z != kNone && e < n.x && e < n.y) renderTriangle(2 * e, v.x, v.y, v.z);
    if (v.w != kNone && e < n.z && e < n.w) renderTriangle(2 * e + 1, v.y, v.x, v.w);
}
