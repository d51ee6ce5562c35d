#version 460
#extension GL_GOOGLE_include_directive : require
// Once per reconstruction: which triangle covers each supersample, and where. The exact
// coverage tests of raster.h decide (the renderer's convention at an output of
// 3w × 3h, so every supersample lies in exactly one triangle); the barycentric weights are
// divided in fp64 like core's MeshRenderer::locateSamples, so the hits match core's.
#include "../common.glsl"
#include "surface.glsl"
#include "triangle_pass.glsl"

void visitTriangle(uint slot, uvec3 ids, SampleBox box) {
    const uint w = push.width;
    const uint in_w = push.input_width, in_h = push.input_height;
    const uint out_w = push.out_width, out_h = push.out_height;
    int64_t px[3], py[3];
    for (int k = 0; k < 3; ++k) {
        px[k] = vertexCoord(ids[k] % w, out_w);
        py[k] = vertexCoord(ids[k] / w, out_h);
    }
    for (uint y = box.y_lo; y <= box.y_hi; ++y) {
        const int64_t sv = sampleCoord(y, in_h, out_h);
        const int dir_v = sampleDirection(sv, in_h, out_h);
        for (uint x = box.x_lo; x <= box.x_hi; ++x) {
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
            const double total = double(weight[0]) + double(weight[1]) + double(weight[2]);
            const vec3 lambda = vec3(double(weight[0]) / total, double(weight[1]) / total, double(weight[2]) / total);
            imageStore(hits, supersampleAt(x, y), uvec4(slot, floatBitsToUint(lambda)));
        }
    }
}
