#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Resampling a tetrahedral mesh's piecewise-linear function (core/volume/tet_resample.h): one
// invocation per slot, the output samples in the tet's box within the slab, each sample the tet
// owns stored as core's value. Operation for operation core's scanTet in int64 (the exact face
// functions, the symbolic push on ties) and in fp64 with every double `precise` (no fused
// multiply-add, no reassociation), so the floats are core's bit for bit. Tets that core's bound
// would not test in int64, or whose box would loop too long, are deferred to the host
// (tet_resample_layout.h).
#include "raster.h"
#include "tet_resample_layout.h"

layout(local_size_x = kTetResampleGroupSize) in;

layout(push_constant, std430) uniform Push {
    TetResamplePush push;
};

layout(binding = kTetResampleBindingVertices, rgba32ui) uniform readonly uimageBuffer tet_vertices;
layout(binding = kTetResampleBindingValues, r32f) uniform readonly imageBuffer vertex_values;
layout(binding = kTetResampleBindingSampleRanges, r32ui) uniform readonly uimageBuffer sample_ranges;
layout(binding = kTetResampleBindingSlab, r32f) uniform writeonly imageBuffer slab;
layout(binding = kTetResampleBindingDeferred, std430) buffer Deferred {
    uint deferred_count;
    uint deferred_bits[];
};

const uint kFreeSlot = 0xffffffffu;  // TetMesh: a free slot's first vertex is kNoTet

// Where axis a's tables start in sample_ranges: 2 · n per earlier axis.
uint rangesOffset(uint a) {
    uint offset = 0u;
    for (uint b = 0u; b < a; ++b) offset += 2u * push.in_size[b];
    return offset;
}
// The first output index along a whose sample lies at or after input index i, and the end of
// those at or before it.
uint firstSampleFrom(uint a, uint i) { return imageLoad(sample_ranges, int(rangesOffset(a) + i)).x; }
uint endSampleTo(uint a, uint i) { return imageLoad(sample_ranges, int(rangesOffset(a) + push.in_size[a] + i)).x; }

// The exact unit along a: 2m per input voxel (vertexCoord).
int64_t unitOf(uint a) { return vertexCoord(1u, push.out_size[a]); }

// Marks slot t for the host; each slot counted once, however many slabs defer it.
void defer(uint t) {
    const uint bit = 1u << (t & 31u);
    if ((atomicOr(deferred_bits[t >> 5u], bit) & bit) == 0u) atomicAdd(deferred_count, 1u);
}

// One component of u × w, as core's crossComponent.
int64_t crossComponent(int64_t u1, int64_t u2, int64_t w1, int64_t w2) { return u1 * w2 - u2 * w1; }
i64vec3 cross64(i64vec3 u, i64vec3 w) {
    return i64vec3(crossComponent(u.y, u.z, w.y, w.z), crossComponent(u.z, u.x, w.z, w.x),
                   crossComponent(u.x, u.y, w.x, w.y));
}

void main() {
    const uint t = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * kTetResampleGroupSize +
                   gl_LocalInvocationID.x;
    if (t >= push.slot_count) return;
    const uvec4 ids = imageLoad(tet_vertices, int(t));
    if (ids.x == kFreeSlot) return;

    // The vertices' index coordinates in the whole input, their box, and the samples' box
    // within the window.
    const uint slice = push.mesh_size[0] * push.mesh_size[1];
    uvec3 index[4];
    for (uint k = 0u; k < 4u; ++k) {
        const uint id = ids[k], z = id / slice, rest = id - z * slice, y = rest / push.mesh_size[0];
        index[k] = uvec3(rest - y * push.mesh_size[0], y, z) +
                   uvec3(push.vertex_offset[0], push.vertex_offset[1], push.vertex_offset[2]);
    }
    const uvec3 lo = min(min(index[0], index[1]), min(index[2], index[3]));
    const uvec3 hi = max(max(index[0], index[1]), max(index[2], index[3]));
    uvec3 first, last;
    for (uint a = 0u; a < 3u; ++a) {
        first[a] = max(firstSampleFrom(a, lo[a]), push.out_begin[a]);
        last[a] = min(endSampleTo(a, hi[a]), push.out_end[a]);
        if (first[a] >= last[a]) return;
    }

    // Deferred, whatever the slab: core's int64 bound (tet_resample.h), and the box's loop trips.
    precise double bound = 6.0lf;
    for (uint a = 0u; a < 3u; ++a) bound *= double(unitOf(a)) * double(hi[a] - lo[a]);
    const uint64_t rows = uint64_t(last.y - first.y) * uint64_t(last.z - first.z);
    const uint64_t trips = rows + rows * uint64_t(last.x - first.x);
    if (bound >= ldexp(1.0lf, int(push.narrow_log2)) || trips > uint64_t(push.max_box_trips)) {
        defer(t);
        return;
    }
    first.y = max(first.y, push.slab_begin_y);
    last.y = min(last.y, push.slab_end_y);
    first.z = max(first.z, push.slab_begin_z);
    last.z = min(last.z, push.slab_end_z);
    if (first.y >= last.y || first.z >= last.z) return;

    // The four face functions f_i(p) = g_i · (p − anchor_i) in the exact units, per component
    // over the faces (core's faceFunctionsOf; its comment derives them).
    i64vec3 v[4];
    for (uint k = 0u; k < 4u; ++k) v[k] = i64vec3(index[k]) * i64vec3(unitOf(0u), unitOf(1u), unitOf(2u));
    const i64vec3 d1 = v[1] - v[0], d2 = v[2] - v[0], d3 = v[3] - v[0];
    const i64vec3 g0 = cross64(v[3] - v[1], v[2] - v[1]), g1 = cross64(d2, d3), g2 = cross64(d3, d1),
                  g3 = cross64(d1, d2);
    const i64vec4 gx = i64vec4(g0.x, g1.x, g2.x, g3.x), gy = i64vec4(g0.y, g1.y, g2.y, g3.y),
                  gz = i64vec4(g0.z, g1.z, g2.z, g3.z);
    const i64vec4 anchor_x = i64vec4(v[1].x, v[0].x, v[0].x, v[0].x);
    const i64vec4 anchor_y = i64vec4(v[1].y, v[0].y, v[0].y, v[0].y);
    const i64vec4 anchor_z = i64vec4(v[1].z, v[0].z, v[0].z, v[0].z);
    const int64_t total = g1.x * d1.x + g1.y * d1.y + g1.z * d1.z;
    // Per face the axis of g's first nonzero component and whether it is positive: a sample on
    // the face's plane pushed by σ is inside when σ_axis · g_axis > 0.
    const i64vec4 zero = i64vec4(0);
    const uvec4 tie_axis = mix(mix(uvec4(2u), uvec4(1u), notEqual(gy, zero)), uvec4(0u), notEqual(gx, zero));
    const i64vec4 tie_component = mix(mix(gz, gy, notEqual(gy, zero)), gx, notEqual(gx, zero));
    const uvec4 tie_positive = uvec4(greaterThan(tie_component, zero));

    const double values[4] = double[4](double(imageLoad(vertex_values, int(ids.x)).x),
                                       double(imageLoad(vertex_values, int(ids.y)).x),
                                       double(imageLoad(vertex_values, int(ids.z)).x),
                                       double(imageLoad(vertex_values, int(ids.w)).x));
    const double total_d = double(total);
    const int64_t high_x = vertexCoord(push.in_size[0] - 1u, push.out_size[0]);
    const int64_t high_y = vertexCoord(push.in_size[1] - 1u, push.out_size[1]);
    const int64_t high_z = vertexCoord(push.in_size[2] - 1u, push.out_size[2]);
    const uint width = push.out_end[0] - push.out_begin[0];
    const uint height = push.slab_end_y - push.slab_begin_y;
    for (uint z = first.z; z < last.z; ++z) {
        const int64_t sz = sampleCoord(z, push.in_size[2], push.out_size[2]);
        for (uint y = first.y; y < last.y; ++y) {
            const int64_t sy = sampleCoord(y, push.in_size[1], push.out_size[1]);
            // Along a row each f_i is base_i + g_i.x · (X − anchor_i.x).
            const i64vec4 base = gy * (sy - anchor_y) + gz * (sz - anchor_z);
            // Bit a set where the push σ_a is −1: the sample on the box's high side along a.
            const uint back_yz = (sy == high_y ? 2u : 0u) | (sz == high_z ? 4u : 0u);
            const uint row = width * ((y - push.slab_begin_y) + height * (z - push.slab_begin_z));
            // A convex tet's samples along a row are consecutive (core's scanTet): stop on leaving.
            bool entered = false;
            for (uint x = first.x; x < last.x; ++x) {
                const int64_t sx = sampleCoord(x, push.in_size[0], push.out_size[0]);
                const i64vec4 f = base + gx * (sx - anchor_x);
                const uint back = back_yz | (sx == high_x ? 1u : 0u);
                const uvec4 tie_inside = uvec4(notEqual(tie_positive, (uvec4(back) >> tie_axis) & 1u));
                const uvec4 inside = uvec4(greaterThan(f, zero)) | (uvec4(equal(f, zero)) & tie_inside);
                if (!all(bvec4(inside))) {
                    if (entered) break;
                    continue;
                }
                entered = true;
                // core's resampleTetsInto: λ_i = f_i / orient, divided (a weight f_i = orient is
                // exactly 1), summed from 0.0 in vertex order, in double, stored as float.
                precise double sum = 0.0lf;
                sum += double(f.x) / total_d * values[0];
                sum += double(f.y) / total_d * values[1];
                sum += double(f.z) / total_d * values[2];
                sum += double(f.w) / total_d * values[3];
                imageStore(slab, int(row + x - push.out_begin[0]), vec4(float(sum)));
            }
        }
    }
}
