// What every Delaunay flip kernel binds (delaunay_layout.h) and how it reads the mesh.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "../layout.h"
#include "../fixed_position.h"
#include "../image/sederberg.h"
#include "delaunay_layout.h"

layout(local_size_x = kGroupSize) in;

layout(push_constant) uniform Push {
    DelaunayPush push;
};

layout(binding = kDelaunayBindingEdgeVertices, r32ui) uniform uimageBuffer edge_vertices;
layout(binding = kDelaunayBindingEdgeNeighbours, r32ui) uniform uimageBuffer edge_neighbours;
layout(binding = kDelaunayBindingPositions, rg32i) uniform readonly iimageBuffer positions;
layout(binding = kDelaunayBindingEdgeStates, r32ui) uniform uimageBuffer edge_states;
layout(binding = kDelaunayBindingTallies, r32ui) uniform uimageBuffer tallies;

layout(binding = kDelaunayBindingEdgeLists, r32ui) uniform uimageBuffer edge_lists;
layout(binding = kDelaunayBindingListLengths, r32ui) uniform uimageBuffer list_lengths;

// The work list this round goes through, and the one it fills for the next.
uint roundList() { return push.round & 1u; }
uint nextList() { return 1u - (push.round & 1u); }

// This invocation's edge: its entry of the round's work list, or kNone past the list's end.
uint invocationEdge() {
    const uint i = push.first_edge + gl_GlobalInvocationID.x;
    if (i >= imageLoad(list_lengths, int(roundList())).x) return kNone;
    return imageLoad(edge_lists, int(roundList() * push.edge_count + i)).x;
}

// Puts edge g (or nothing, for kNone) on the next round's work list, once: the first to set
// its kEdgeQueued bit appends it. The next round's marks write its state afresh, clearing it.
void queueForNextRound(uint g) {
    if (g == kNone) return;
    if ((imageAtomicOr(edge_states, int(g), kEdgeQueued) & kEdgeQueued) != 0u) return;
    const uint slot = imageAtomicAdd(list_lengths, int(nextList()), 1u);
    imageStore(edge_lists, int(nextList() * push.edge_count + slot), uvec4(g));
}

uint stateOf(uint e) { return imageLoad(edge_states, int(e)).x & kEdgeStateMask; }

uint vertexWord(uint e, uint i) { return imageLoad(edge_vertices, int(4u * e + i)).x; }
uint neighbourWord(uint e, uint i) { return imageLoad(edge_neighbours, int(4u * e + i)).x; }
uvec4 verticesOf(uint e) { return uvec4(vertexWord(e, 0u), vertexWord(e, 1u), vertexWord(e, 2u), vertexWord(e, 3u)); }
uvec4 neighboursOf(uint e) {
    return uvec4(neighbourWord(e, 0u), neighbourWord(e, 1u), neighbourWord(e, 2u), neighbourWord(e, 3u));
}
Position positionOf(uint v) {
    const ivec2 p = imageLoad(positions, int(v)).xy;
    return Position(p.x, p.y);
}
