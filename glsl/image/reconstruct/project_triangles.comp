#version 460
#extension GL_GOOGLE_include_directive : require
// Projects ρ (the supersamples: Dᵀ of the residual, or of 1 for the weights) onto each
// triangle's six basis functions: per vertex Σ λ·ρ, per edge Σ 4·λp·λq·ρ over the triangle's
// supersamples. Each triangle adds its sums to the three half-edges facing it, which only it
// writes: gathers, no atomics, so the sums do not depend on timing. The host zeroes the sums
// first; a triangle spread over several parts adds each part's share in the parts' order.
#include "../common.glsl"
#include "surface.glsl"
#include "triangle_pass.glsl"

void visitTriangle(uint slot, uvec3 ids, SampleBox box) {
    vec4 value_sum[3] = vec4[3](vec4(0), vec4(0), vec4(0));
    vec4 bubble_sum[3] = vec4[3](vec4(0), vec4(0), vec4(0));
    bool covers = false;
    for (uint y = box.y_lo; y <= box.y_hi; ++y) {
        for (uint x = box.x_lo; x <= box.x_hi; ++x) {
            const int sample_index = supersampleAt(x, y);
            const uvec4 hit = imageLoad(hits, sample_index);
            if (hit.x != slot) continue;
            covers = true;
            const vec3 l = uintBitsToFloat(hit.yzw);
            const vec4 rho = imageLoad(supersamples, sample_index);
            value_sum[0] += l.x * rho;
            value_sum[1] += l.y * rho;
            value_sum[2] += l.z * rho;
            bubble_sum[0] += (4 * l.y * l.z) * rho;
            bubble_sum[1] += (4 * l.z * l.x) * rho;
            bubble_sum[2] += (4 * l.x * l.y) * rho;
        }
    }
    if (!covers) return;
    const uvec3 edges = slotEdges(slot);
    for (int k = 0; k < 3; ++k) {
        const int half_edge = int(halfEdgeFacing(edges[k], ids[k]));
        imageStore(half_edge_value_sums, half_edge, imageLoad(half_edge_value_sums, half_edge) + value_sum[k]);
        imageStore(half_edge_bubble_sums, half_edge, imageLoad(half_edge_bubble_sums, half_edge) + bubble_sum[k]);
    }
}
