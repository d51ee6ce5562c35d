#version 460
#extension GL_GOOGLE_include_directive : require
// Step 3 of a simplification round: the chosen winners collapse, one invocation each, as
// core's collapseEdge does (its comments explain each change), and the vertex that stays takes
// the other's quadric into its own and, if the collapse moves it, its target as its position.
// Winners' regions are disjoint and hold every record a collapse reads or writes, so they run
// in any order to the same mesh.
#include "collapse_rule.glsl"

layout(binding = kSimplifyBindingCollapses, r32ui) uniform readonly uimageBuffer collapses;
layout(binding = kSimplifyBindingTargets, rg32i) uniform readonly iimageBuffer targets;

// Marks v and its neighbours changed, for the next round's candidates.
void markRing(uint v) {
    imageStore(changed, int(v), uvec4(1u));
    for (Walk w = beginWalk(v); w.f != kNone; advance(w)) imageStore(changed, int(otherEnd(verticesOf(w.f), v)), uvec4(1u));
}

void setVertices(uint e, uvec4 v) { imageStore(edge_vertices, int(e), v); }
void setNeighbours(uint e, uvec4 n) { imageStore(edge_neighbours, int(e), n); }

void replaceLink(uint edge, uint old_link, uint new_link) {
    uvec4 n = neighboursOf(edge);
    n = uvec4(n.x == old_link ? new_link : n.x, n.y == old_link ? new_link : n.y, n.z == old_link ? new_link : n.z,
              n.w == old_link ? new_link : n.w);
    setNeighbours(edge, n);
}

// A triangle of the collapsing edge: its third vertex, its edge to–third (kept) and from–third.
struct Side {
    uint third, kept, removed;
};

void main() {
    const uint index = push.first_edge + gl_GlobalInvocationID.x;
    if (index >= push.edge_count) return;
    const uint entry = imageLoad(collapses, int(index)).x;
    const uint e = entry & ~(kCollapseBIntoA | kCollapseMoves);
    const bool b_into_a = (entry & kCollapseBIntoA) != 0u, moves = (entry & kCollapseMoves) != 0u;
    const uvec4 ev = verticesOf(e), en = neighboursOf(e);  // (a, b, l, r), (bl, la, ar, rb)
    const uint from = b_into_a ? ev.y : ev.x, to = b_into_a ? ev.x : ev.y;
    // `from` and its neighbours, whose edges change, for the next round's candidates (the host
    // cleared the marks; core's markRingChanged).
    markRing(from);
    uint at_from[kMaxEdgesAtFrom];
    uint at_from_count = 0u;
    for (Walk w = beginWalk(from); w.f != kNone; advance(w)) at_from[at_from_count++] = w.f;
    Side sides[2];
    uint side_count = 0u;
    if (ev.z != kNone) sides[side_count++] = Side(ev.z, b_into_a ? en.y : en.x, b_into_a ? en.x : en.y);
    if (ev.w != kNone) sides[side_count++] = Side(ev.w, b_into_a ? en.z : en.w, b_into_a ? en.w : en.z);

    for (uint s = 0u; s < side_count; ++s) {
        const Side side = sides[s];
        const uvec4 rv = verticesOf(side.removed), rn = neighboursOf(side.removed);
        const bool outer_is_right = rv.z == to;
        const uint x = outer_is_right ? rv.w : rv.z;
        const uint outer0 = outer_is_right ? rn.z : rn.x, outer1 = outer_is_right ? rn.w : rn.y;
        uvec4 kv = verticesOf(side.kept), kn = neighboursOf(side.kept);
        const bool kept_left = kv.z == from;
        if (x == kNone) {
            if (kept_left) {
                kv.z = kNone;
                kn.xy = uvec2(kNone);
            } else {
                kv.w = kNone;
                kn.zw = uvec2(kNone);
            }
            setVertices(side.kept, kv);
            setNeighbours(side.kept, kn);
            continue;
        }
        const uvec4 first_outer = verticesOf(outer0);
        const bool first_at_from = first_outer.x == from || first_outer.y == from;
        uint at_to = first_at_from ? outer0 : outer1;
        const uint at_third = first_at_from ? outer1 : outer0;
        for (uint t = 0u; t < side_count; ++t)
            if (at_to == sides[t].removed) at_to = sides[t].kept;
        if (kept_left) {  // (a, b, l): bl = b–l, la = l–a
            kv.z = x;
            kn.x = kv.y == to ? at_to : at_third;
            kn.y = kv.x == to ? at_to : at_third;
        } else {  // (b, a, r): ar = a–r, rb = r–b
            kv.w = x;
            kn.z = kv.x == to ? at_to : at_third;
            kn.w = kv.y == to ? at_to : at_third;
        }
        setVertices(side.kept, kv);
        setNeighbours(side.kept, kn);
        replaceLink(at_to, side.removed, side.kept);
        replaceLink(at_third, side.removed, side.kept);
        uvec4 opposite = verticesOf(at_third);
        opposite.z = opposite.z == from ? to : opposite.z;
        opposite.w = opposite.w == from ? to : opposite.w;
        setVertices(at_third, opposite);
    }

    for (uint k = 0u; k < at_from_count; ++k) {
        const uint f = at_from[k];
        bool removed = f == e;
        for (uint s = 0u; s < side_count; ++s) removed = removed || f == sides[s].removed;
        if (removed) continue;
        uvec4 fv = verticesOf(f);
        const uvec4 fn = neighboursOf(f);
        if (fv.x == from) fv.x = to;
        else fv.y = to;
        setVertices(f, fv);
        const bool to_is_a = fv.x == to;
        const uint opposites[2] = {fv.z != kNone ? (to_is_a ? fn.x : fn.y) : kNone,
                                   fv.w != kNone ? (to_is_a ? fn.w : fn.z) : kNone};
        for (uint o = 0u; o < 2u; ++o) {
            if (opposites[o] == kNone) continue;
            uvec4 ov = verticesOf(opposites[o]);
            ov.z = ov.z == from ? to : ov.z;
            ov.w = ov.w == from ? to : ov.w;
            setVertices(opposites[o], ov);
        }
    }

    imageStore(vertex_first, int(from), uvec4(kNone));
    for (uint s = 0u; s < side_count; ++s) {
        imageStore(vertex_first, int(to), uvec4(sides[s].kept));
        imageStore(vertex_first, int(sides[s].third), uvec4(sides[s].kept));
    }
    setVertices(e, uvec4(kNone));
    setNeighbours(e, uvec4(kNone));
    for (uint s = 0u; s < side_count; ++s) {
        setVertices(sides[s].removed, uvec4(kNone));
        setNeighbours(sides[s].removed, uvec4(kNone));
    }

    // The quadrics' sum, word by word as core's operator+= adds them.
    for (uint k = 0u; k < kQuadricDoubles; ++k) {
        const double sum = quadricWord(to, k) + quadricWord(from, k);
        imageStore(quadrics, int(to * kQuadricDoubles + k), uvec4(unpackDouble2x32(sum), 0u, 0u));
    }
    // A moved vertex changes the triangles around it: its new ring, marked after the records'
    // changes (this invocation's own writes, which it reads back in program order).
    if (moves) {
        imageStore(positions, int(to), imageLoad(targets, int(e)));
        markRing(to);
    }
}
