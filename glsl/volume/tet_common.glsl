// Shared by the tetrahedral flip kernels: the bindings of tet_layout.h, the push constants, and
// the per-tet formulas of core/volume/tet_cost.cpp (content, variance, gradient, face SCF, a
// tet's cost), operation for operation in fp64: every double intermediate is `precise`, so no
// multiply-add is fused and no expression reassociated, and the kernels round exactly as the C++
// compiled for x86-64 (no FMA without -mfma). Mesh words: core/volume/tet_mesh.h's glossary.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "tet_layout.h"
#include "tet_orient.h"

layout(local_size_x = kTetGroupSize) in;

layout(push_constant, std430) uniform Push {
    TetPush push;
};

layout(binding = kTetBindingVertices, rgba32ui) uniform uimageBuffer tet_vertices;
layout(binding = kTetBindingNeighbours, rgba32ui) uniform uimageBuffer tet_neighbours;
layout(binding = kTetBindingValues, rg32ui) uniform readonly uimageBuffer vertex_values;
layout(binding = kTetBindingCost, rg32ui) uniform uimageBuffer tet_cost;
layout(binding = kTetBindingGradient, rg32ui) uniform uimageBuffer tet_gradient;
layout(binding = kTetBindingState, r32ui) uniform uimageBuffer tet_state;
layout(binding = kTetBindingClaimHigh, r32ui) uniform uimageBuffer claim_high;
layout(binding = kTetBindingClaimLow, r32ui) uniform uimageBuffer claim_low;
layout(binding = kTetBindingFreeSlots, r32ui) uniform uimageBuffer free_slots;
layout(binding = kTetBindingFreed, r32ui) uniform uimageBuffer freed_slots;
layout(binding = kTetBindingActive, r32ui) uniform uimageBuffer active_list;
layout(binding = kTetBindingEvaluate, r32ui) uniform uimageBuffer eval_list;
layout(binding = kTetBindingCandidates, rg32ui) uniform uimageBuffer candidate_list;
layout(binding = kTetBindingMasks, r32ui) uniform uimageBuffer masks;
layout(binding = kTetBindingWordPrefix, rg32ui) uniform uimageBuffer word_prefix;
layout(binding = kTetBindingBlocks, rgba32ui) uniform uimageBuffer blocks;
layout(binding = kTetBindingPositions, rgba32i) uniform readonly iimageBuffer vertex_positions;
layout(binding = kTetBindingCarried, rg32ui) uniform uimageBuffer carried_list;
layout(binding = kTetBindingControl, std430) buffer ControlBlock {
    TetControl control;
};
layout(binding = kTetBindingArgs, std430) buffer ArgsBlock {
    uvec4 args[kTetStepCount];
};

const uint kNoTet = 0xffffffffu;

// The item of this invocation in a (possibly two-dimensional) dispatch of kTetGroupSize groups.
uint invocationIndex() {
    return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * kTetGroupSize + gl_LocalInvocationID.x;
}

uvec4 verticesOf(uint t) { return imageLoad(tet_vertices, int(t)); }
uvec4 neighboursOf(uint t) { return imageLoad(tet_neighbours, int(t)); }
bool inUse(uint t) { return imageLoad(tet_vertices, int(t)).x != kNoTet; }

uvec4 doubleTexel(double value) { return uvec4(unpackDouble2x32(value), 0u, 0u); }

double valueOf(uint v) { return packDouble2x32(imageLoad(vertex_values, int(v)).xy); }
dvec3 gradientOf(uint t) {
    return dvec3(packDouble2x32(imageLoad(tet_gradient, int(3u * t)).xy),
                 packDouble2x32(imageLoad(tet_gradient, int(3u * t + 1u)).xy),
                 packDouble2x32(imageLoad(tet_gradient, int(3u * t + 2u)).xy));
}
bool isFlat(uint t) { return (imageLoad(tet_state, int(t)).x & kTetStateFlat) != 0u; }

double spacingOf(uint axis) {
    return packDouble2x32(uvec2(push.spacing_bits[2u * axis], push.spacing_bits[2u * axis + 1u]));
}
double contentScale() { return packDouble2x32(uvec2(push.content_scale_bits[0], push.content_scale_bits[1])); }

// Index coordinates of vertex v (core's coordinatesOf, cached as TetCosts caches them).
ivec3 positionOf(uint v) { return imageLoad(vertex_positions, int(v)).xyz; }

int64_t orientOf(uint a, uint b, uint c, uint d) {
    const ivec3 pa = positionOf(a), pb = positionOf(b), pc = positionOf(c), pd = positionOf(d);
    return tetOrient(pa.x, pa.y, pa.z, pb.x, pb.y, pb.z, pc.x, pc.y, pc.z, pd.x, pd.y, pd.z);
}
int64_t orientOf(uvec4 t) { return orientOf(t.x, t.y, t.z, t.w); }

// content(t) = orient · sx · sy · sz / 6 (tet_cost.cpp's contentFrom).
double contentFromOrient(int64_t orient) {
    precise double content = double(orient) * contentScale();
    return content;
}
double contentOfTet(uvec4 t) { return contentFromOrient(orientOf(t)); }
// TetCosts::content(t), recomputed from the record rather than cached: the same operations as
// the cache's, so the same bits, and 8 bytes a slot less; 0 for a free slot, as in the cache.
double contentOf(uint t) {
    const uvec4 v = verticesOf(t);
    return v.x == kNoTet ? 0.0lf : contentOfTet(v);
}

// Σ (z_i − mean)² / 4 in record order (varianceFrom).
double varianceOfTet(uvec4 t) {
    const double z[4] = double[4](valueOf(t.x), valueOf(t.y), valueOf(t.z), valueOf(t.w));
    precise double mean = (z[0] + z[1] + z[2] + z[3]) / 4.0lf;
    precise double sum = 0.0lf;
    for (uint i = 0u; i < 4u; ++i) {
        precise double d = z[i] - mean;
        sum += d * d;
    }
    precise double variance = sum / 4.0lf;
    return variance;
}

bool flatTet(uvec4 t) {
    const double z0 = valueOf(t.x);
    return z0 == valueOf(t.y) && z0 == valueOf(t.z) && z0 == valueOf(t.w);
}

// ∇P in the physical frame (gradientFrom): exact integer cross products over the determinant.
dvec3 gradientOfTet(uvec4 t) {
    const ivec3 p0 = positionOf(t.x);
    const i64vec3 e1 = i64vec3(positionOf(t.y) - p0), e2 = i64vec3(positionOf(t.z) - p0), e3 = i64vec3(positionOf(t.w) - p0);
    const i64vec3 c23 = i64vec3(e2.y * e3.z - e2.z * e3.y, e2.z * e3.x - e2.x * e3.z, e2.x * e3.y - e2.y * e3.x);
    const i64vec3 c31 = i64vec3(e3.y * e1.z - e3.z * e1.y, e3.z * e1.x - e3.x * e1.z, e3.x * e1.y - e3.y * e1.x);
    const i64vec3 c12 = i64vec3(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
    const int64_t det = e1.x * c23.x + e1.y * c23.y + e1.z * c23.z;
    const double z0 = valueOf(t.x);
    precise double dz1 = valueOf(t.y) - z0;
    precise double dz2 = valueOf(t.z) - z0;
    precise double dz3 = valueOf(t.w) - z0;
    precise double g0 = (dz1 * double(c23.x) + dz2 * double(c31.x) + dz3 * double(c12.x)) / (double(det) * spacingOf(0u));
    precise double g1 = (dz1 * double(c23.y) + dz2 * double(c31.y) + dz3 * double(c12.y)) / (double(det) * spacingOf(1u));
    precise double g2 = (dz1 * double(c23.z) + dz2 * double(c31.z) + dz3 * double(c12.z)) / (double(det) * spacingOf(2u));
    return dvec3(g0, g1, g2);
}

// |g1|·|g2| as sqrt(|g1|²·|g2|²) (faceScf's first term).
double normProduct(dvec3 g1, dvec3 g2) {
    precise double n1 = g1.x * g1.x + g1.y * g1.y + g1.z * g1.z;
    precise double n2 = g2.x * g2.x + g2.y * g2.y + g2.z * g2.z;
    precise double norms = sqrt(n1 * n2);
    return norms;
}

// scf = |g1|·|g2| − g1·g2 (tet_cost.cpp's faceScf).
double faceScf(dvec3 g1, dvec3 g2) {
    precise double dot = g1.x * g2.x + g1.y * g2.y + g1.z * g2.z;
    precise double scf = normProduct(g1, g2) - dot;
    return scf;
}

// content(t) · w(t) of slot t from the cache (TetCosts::costFromCache).
double cachedCost(uint t) {
    if (push.face_scf == 0u) {
        precise double cost = contentOf(t) * varianceOfTet(verticesOf(t));
        return cost;
    }
    const dvec3 g = gradientOf(t);
    const uvec4 n = neighboursOf(t);
    precise double sum = 0.0lf;
    for (uint f = 0u; f < 4u; ++f)
        if (n[f] != kNoTet) sum += faceScf(g, gradientOf(n[f]));
    precise double cost = contentOf(t) * (sum / 4.0lf);
    return cost;
}

// Lists slot t in the active list (once: the state bit), or in the evaluation list.
void listActive(uint t) {
    if ((imageAtomicOr(tet_state, int(t), kTetStateActive) & kTetStateActive) == 0u)
        imageStore(active_list, int(atomicAdd(control.active_count, 1u)), uvec4(t));
}
void listEval(uint t) {
    if ((imageAtomicOr(tet_state, int(t), kTetStateEval) & kTetStateEval) == 0u)
        imageStore(eval_list, int(atomicAdd(control.eval_count, 1u)), uvec4(t));
}
