#include "edge_collapse.h"

#include <algorithm>
#include <cassert>
#include <bit>

namespace ddt {

namespace {

uint32_t otherEnd(const EdgeVertices& v, uint32_t p) { return v.a == p ? v.b : v.a; }

// The triangles on the sides of edge f, positive: (a, b, l) and (b, a, r) where they exist.
template <typename Visit>
void forEachSide(const EdgeVertices& v, Visit visit) {
    if (v.l != kNone) visit(v.a, v.b, v.l);
    if (v.r != kNone) visit(v.b, v.a, v.r);
}

void replaceLink(Mesh& mesh, uint32_t edge, uint32_t old_link, uint32_t new_link) {
    EdgeNeighbours& n = mesh.neighbours[edge];
    for (uint32_t* slot : {&n.bl, &n.la, &n.ar, &n.rb})
        if (*slot == old_link) *slot = new_link;
}

}  // namespace

VertexEdges::VertexEdges(const Mesh& mesh) : first(mesh.vertexCount(), kNone) {
    for (uint32_t e = mesh.edgeCount(); e-- > 0;) {  // each vertex's lowest edge id
        if (removedEdge(mesh, e)) continue;
        first[mesh.vertices[e].a] = first[mesh.vertices[e].b] = e;
    }
}

HullPlace hullPlaceOf(const Mesh& mesh, const VertexEdges& edges, uint32_t v) {
    uint32_t ends[2], count = 0;
    forEachEdgeAt(mesh, edges, v, [&](uint32_t f) {
        const EdgeVertices& fv = mesh.vertices[f];
        if ((fv.l == kNone || fv.r == kNone) && count < 2) ends[count++] = otherEnd(fv, v);
    });
    if (count < 2) return HullPlace::inside;
    return orientationSign(mesh, ends[0], v, ends[1]) == 0 ? HullPlace::straight : HullPlace::corner;
}

bool canCollapse(const Mesh& mesh, const VertexEdges& edges, Collapse collapse) {
    const EdgeVertices& ev = mesh.vertices[collapse.edge];
    const uint32_t from = collapse.from(mesh), to = collapse.to(mesh);
    const uint32_t from_sides = collapseSides(mesh, from);
    if (std::popcount(from_sides) >= 2) return false;  // a corner, or on a locked side
    const HullPlace from_hull = hullPlaceOf(mesh, edges, from);
    if (from_hull == HullPlace::corner) return false;  // the hull would lose it
    if (from_hull != HullPlace::inside && ev.l != kNone && ev.r != kNone) return false;  // a hull vertex leaves the hull
    const Position target = collapse.moves ? collapse.target : positionOf(mesh, to);
    if (collapse.moves) {
        const uint32_t kept = from_sides | collapseSides(mesh, to);
        if ((collapseSides(mesh, target) & kept) != kept) return false;
        // On the hull, only along a side of the rectangle, where the hull is straight.
        auto staysOnHull = [&](uint32_t v, HullPlace place) {
            return place == HullPlace::inside || (place == HullPlace::straight && rectangleSides(mesh, v) != 0);
        };
        if (!staysOnHull(from, from_hull) || !staysOnHull(to, hullPlaceOf(mesh, edges, to))) return false;
    }
    // Valence: `to` ends with the edges of both but e and the removed ones.
    uint32_t valence = 0;
    forEachEdgeAt(mesh, edges, from, [&](uint32_t) { ++valence; });
    forEachEdgeAt(mesh, edges, to, [&](uint32_t) { ++valence; });
    if (valence - 2 - uint32_t(ev.l != kNone) - uint32_t(ev.r != kNone) > kMaxCollapseValence) return false;
    // Link condition: the common neighbours of a and b are e's adjacent vertices.
    uint32_t common = 0;
    bool linked = true;
    forEachEdgeAt(mesh, edges, from, [&](uint32_t f) {
        const uint32_t x = otherEnd(mesh.vertices[f], from);
        if (x == to) return;
        forEachEdgeAt(mesh, edges, to, [&](uint32_t g) {
            if (otherEnd(mesh.vertices[g], to) != x) return;
            linked = linked && (x == ev.l || x == ev.r);
            ++common;
        });
    });
    if (!linked || common != uint32_t(ev.l != kNone) + uint32_t(ev.r != kNone)) return false;
    // No fold-over: the triangles around `from` (and `to`, if it moves) that stay are still
    // positive with the merged vertex at its place.
    auto placed = [&](uint32_t v) { return v == from || v == to ? target : positionOf(mesh, v); };
    auto staysPositive = [&](uint32_t centre, uint32_t other) {
        bool positive = true;
        forEachEdgeAt(mesh, edges, centre, [&](uint32_t f) {
            if (f == collapse.edge) return;
            forEachSide(mesh.vertices[f], [&](uint32_t p, uint32_t q, uint32_t r) {
                if (p == other || q == other || r == other) return;  // one of e's triangles, which go
                const Position a = placed(p), b = placed(q), c = placed(r);
                positive = positive && positionOrient(a.x, a.y, b.x, b.y, c.x, c.y) > 0;
            });
        });
        return positive;
    };
    return staysPositive(from, to) && (!collapse.moves || staysPositive(to, from));
}

void collapseEdge(Mesh& mesh, VertexEdges& edges, Collapse collapse) {
    const uint32_t e = collapse.edge;
    const EdgeVertices ev = mesh.vertices[e];
    const EdgeNeighbours en = mesh.neighbours[e];
    const uint32_t from = collapse.from(mesh), to = collapse.to(mesh);
    // `from`'s edges, walked before any record changes.
    std::vector<uint32_t> at_from;
    forEachEdgeAt(mesh, edges, from, [&](uint32_t f) { at_from.push_back(f); });
    // Each of e's triangles (a, b, l), (b, a, r): its edge from–third goes, to–third stays.
    struct Side {
        uint32_t third, kept, removed;
    };
    std::vector<Side> sides;
    if (ev.l != kNone) sides.push_back({ev.l, collapse.b_into_a ? en.la : en.bl, collapse.b_into_a ? en.bl : en.la});
    if (ev.r != kNone) sides.push_back({ev.r, collapse.b_into_a ? en.ar : en.rb, collapse.b_into_a ? en.rb : en.ar});

    for (const Side& side : sides) {
        // The removed edge's outer triangle (from, third, x) becomes the kept edge's (to, third, x).
        const EdgeVertices rv = mesh.vertices[side.removed];
        const EdgeNeighbours rn = mesh.neighbours[side.removed];
        const bool outer_is_right = rv.l == to;
        const uint32_t x = outer_is_right ? rv.r : rv.l;
        const uint32_t outer[2] = {outer_is_right ? rn.ar : rn.bl, outer_is_right ? rn.rb : rn.la};
        EdgeVertices& kv = mesh.vertices[side.kept];
        EdgeNeighbours& kn = mesh.neighbours[side.kept];
        const bool kept_left = kv.l == from;
        if (x == kNone) {
            (kept_left ? kv.l : kv.r) = kNone;
            if (kept_left) kn.bl = kn.la = kNone;
            else kn.ar = kn.rb = kNone;
            continue;
        }
        // The outer edge at `to` (from–x, renamed below) and the one at the third vertex.
        const bool first_at_from = mesh.vertices[outer[0]].a == from || mesh.vertices[outer[0]].b == from;
        uint32_t at_to = first_at_from ? outer[0] : outer[1];
        const uint32_t at_third = first_at_from ? outer[1] : outer[0];
        // Where `from` has three neighbours, the outer triangle is (from, l, r): its edge at
        // `from` is the other side's removed edge, whose kept edge takes its place.
        for (const Side& other : sides)
            if (at_to == other.removed) at_to = other.kept;
        auto edgeAt = [&](uint32_t v) { return v == to ? at_to : at_third; };
        if (kept_left) {  // (a, b, l): bl = b–l, la = l–a
            kv.l = x;
            kn.bl = edgeAt(kv.b);
            kn.la = edgeAt(kv.a);
        } else {  // (b, a, r): ar = a–r, rb = r–b
            kv.r = x;
            kn.ar = edgeAt(kv.a);
            kn.rb = edgeAt(kv.b);
        }
        replaceLink(mesh, at_to, side.removed, side.kept);
        replaceLink(mesh, at_third, side.removed, side.kept);
        // The triangle's edge opposite `to` saw `from` there (also reached below, unless every
        // edge at `from` goes: the three-neighbour case).
        EdgeVertices& opposite = mesh.vertices[at_third];
        if (opposite.l == from) opposite.l = to;
        if (opposite.r == from) opposite.r = to;
    }

    // `to` takes `from`'s place in its edges and in the triangles around it.
    auto removed = [&](uint32_t f) {
        return f == e || std::any_of(sides.begin(), sides.end(), [&](const Side& s) { return s.removed == f; });
    };
    for (uint32_t f : at_from) {
        if (removed(f)) continue;
        EdgeVertices& fv = mesh.vertices[f];
        const EdgeNeighbours& fn = mesh.neighbours[f];
        (fv.a == from ? fv.a : fv.b) = to;
        // The edge opposite `to` in each of f's triangles sees `from` as its adjacent vertex.
        const bool to_is_a = fv.a == to;
        for (uint32_t opposite : {fv.l != kNone ? (to_is_a ? fn.bl : fn.la) : kNone,
                                  fv.r != kNone ? (to_is_a ? fn.rb : fn.ar) : kNone}) {
            if (opposite == kNone) continue;
            EdgeVertices& ov = mesh.vertices[opposite];
            if (ov.l == from) ov.l = to;
            if (ov.r == from) ov.r = to;
        }
    }

    if (collapse.moves) {
        assert(!mesh.positions.empty());
        mesh.positions[to] = collapse.target;
    }
    // The walks' starts: a kept edge for `to` and each third vertex (whose edge may have gone).
    edges.first[from] = kNone;
    for (const Side& side : sides) edges.first[to] = edges.first[side.third] = side.kept;
    for (uint32_t f : {e, sides.size() > 0 ? sides[0].removed : kNone, sides.size() > 1 ? sides[1].removed : kNone}) {
        if (f == kNone) continue;
        mesh.vertices[f] = {kNone, kNone, kNone, kNone};
        mesh.neighbours[f] = {kNone, kNone, kNone, kNone};
    }
}

void compactEdges(Mesh& mesh) {
    std::vector<uint32_t> new_id(mesh.edgeCount(), kNone);
    uint32_t next = 0;
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e)
        if (!removedEdge(mesh, e)) new_id[e] = next++;
    auto renumber = [&](uint32_t f) { return f == kNone ? kNone : new_id[f]; };
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
        if (new_id[e] == kNone) continue;
        const EdgeNeighbours& n = mesh.neighbours[e];
        mesh.vertices[new_id[e]] = mesh.vertices[e];
        mesh.neighbours[new_id[e]] = {renumber(n.bl), renumber(n.la), renumber(n.ar), renumber(n.rb)};
    }
    mesh.vertices.resize(next);
    mesh.neighbours.resize(next);
}

}  // namespace ddt
