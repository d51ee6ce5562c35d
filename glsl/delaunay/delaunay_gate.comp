#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// A round's last step: the group counts of the next round's indirect dispatches, from the
// length of the work list this round filled (none once a round has flipped nothing: its list
// stays empty, so the rest of the batch costs a few empty dispatches, not passes over every
// edge; PLATFORM.md: a done flag tested in the shaders still launches every workgroup). And
// this round's list is spent: emptied for the round after next to fill. One invocation.
#include "delaunay_common.glsl"

layout(binding = kDelaunayBindingDispatchArgs, r32ui) uniform writeonly uimageBuffer dispatch_args;

void main() {
    if (gl_GlobalInvocationID.x != 0u) return;
    const uint length = imageLoad(list_lengths, int(nextList())).x;
    const uint per_dispatch = kMaxGroups * kGroupSize;
    const uint dispatches = delaunayDispatches(push.edge_count);
    for (uint d = 0u; d < dispatches; ++d) {
        const uint first = d * per_dispatch;
        const uint entries = length > first ? min(per_dispatch, length - first) : 0u;
        const int slot = int(4u * (nextList() * dispatches + d));  // VkDispatchIndirectCommand, 16 bytes
        imageStore(dispatch_args, slot, uvec4((entries + kGroupSize - 1u) / kGroupSize));
        imageStore(dispatch_args, slot + 1, uvec4(1u));
        imageStore(dispatch_args, slot + 2, uvec4(1u));
    }
    imageStore(list_lengths, int(roundList()), uvec4(0u));
}
