#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Between a round's marks and its choices: the group counts of the indirect dispatches that
// follow (this round's select and flip, the next round's mark), per dispatch of the edges, or
// 0 where this round marked nothing. So a batch's rounds after the last one with marks cost a
// few empty dispatches, not three passes over every edge (PLATFORM.md: a done flag tested in
// the shaders still launches every workgroup). One invocation.
#include "delaunay_common.glsl"

layout(binding = kDelaunayBindingDispatchArgs, r32ui) uniform writeonly uimageBuffer dispatch_args;

void main() {
    if (gl_GlobalInvocationID.x != 0u) return;
    const bool marked = imageLoad(tallies, int(2u * push.round)).x != 0u;
    const uint per_dispatch = kMaxGroups * kGroupSize;
    const uint dispatches = delaunayDispatches(push.edge_count);
    for (uint d = 0u; d < dispatches; ++d) {
        const uint edges = min(per_dispatch, push.edge_count - d * per_dispatch);
        const uint groups = marked ? (edges + kGroupSize - 1u) / kGroupSize : 0u;
        const int slot = int(4u * (push.round * dispatches + d));  // VkDispatchIndirectCommand, 16 bytes
        imageStore(dispatch_args, slot, uvec4(groups));
        imageStore(dispatch_args, slot + 1, uvec4(1u));
        imageStore(dispatch_args, slot + 2, uvec4(1u));
    }
}
