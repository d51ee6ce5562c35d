#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// A round's last step: flip the chosen edges, as core/image/mesh.h's flipEdge does. The quadrilateral
// a, r, b, l gets the diagonal r → l: e's record turns to (r, l, a, b), (la, ar, rb, bl), and
// its four neighbours each get their side facing e rewritten for the new triangles (r, l, a)
// and (l, r, b). A neighbour's ends never change in this round (it shares a triangle with a
// flipping edge, so it is not one), so which side faces e is read safely; another flip may
// rewrite its other side at the same time, which touches other words. The flipped edge and
// its four neighbours go on the next round's list: their quadrilaterals changed.
#include "delaunay_common.glsl"

// The positive triangle (x, y, z) on neighbour g = x–y, its other edges e_yz and e_zx: g's
// left side (l, bl, la) if g runs x → y, else its right side (r, ar, rb).
void attachSide(uint g, uint x, uint z, uint e_yz, uint e_zx) {
    const uint side = vertexWord(g, 0u) == x ? 0u : 1u;
    imageStore(edge_vertices, int(4u * g + 2u + side), uvec4(z));
    imageStore(edge_neighbours, int(4u * g + 2u * side), uvec4(e_yz));
    imageStore(edge_neighbours, int(4u * g + 2u * side + 1u), uvec4(e_zx));
}

void main() {
    const uint e = invocationEdge();
    if (e == kNone) return;
    if (stateOf(e) != kEdgeFlipsNow) return;
    const uvec4 v = verticesOf(e);  // a, b, l, r
    const uvec4 n = neighboursOf(e);  // bl, la, ar, rb
    const uint a = v.x, b = v.y, l = v.z, r = v.w;
    const uint bl = n.x, la = n.y, ar = n.z, rb = n.w;
    const uvec4 flipped_vertices = uvec4(r, l, a, b), flipped_neighbours = uvec4(la, ar, rb, bl);
    for (uint i = 0u; i < 4u; ++i) {
        imageStore(edge_vertices, int(4u * e + i), uvec4(flipped_vertices[i]));
        imageStore(edge_neighbours, int(4u * e + i), uvec4(flipped_neighbours[i]));
    }
    attachSide(la, l, r, ar, e);  // (l, a, r)
    attachSide(ar, a, l, e, la);  // (a, r, l)
    attachSide(rb, r, l, bl, e);  // (r, b, l)
    attachSide(bl, b, r, e, rb);  // (b, l, r)
    queueForNextRound(e);
    for (uint i = 0u; i < 4u; ++i) queueForNextRound(n[i]);
}
