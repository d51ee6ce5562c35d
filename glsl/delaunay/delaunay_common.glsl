// What every Delaunay flip kernel binds (delaunay_layout.h) and how it reads the mesh.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "../layout.h"
#include "../fixed_position.h"
#include "../sederberg.h"
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

// This invocation's edge, or kNone past the last.
uint invocationEdge() {
    const uint e = push.first_edge + gl_GlobalInvocationID.x;
    return e < push.edge_count ? e : kNone;
}

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
