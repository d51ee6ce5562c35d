// The legality, placement and cost of a half-edge collapse as core/simplify/edge_collapse.h
// and placement.h define them, over the texel buffers of simplify_layout.h; the walks around a
// vertex follow core's forEachEdgeAt (the same edges; order does not matter here). The
// arithmetic is core's, operation for operation, in fp64 without fused multiply-add.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "../layout.h"
#include "simplify_layout.h"
#include "quadric_value.h"
#include "../fixed_position.h"
#include "../image/sederberg.h"

layout(local_size_x = kGroupSize) in;

layout(push_constant) uniform Push {
    SimplifyPush push;
};

// The mesh, the walks' starts and the quadrics change only in collapse_edges.comp.
layout(binding = kSimplifyBindingEdgeVertices, rgba32ui) uniform uimageBuffer edge_vertices;
layout(binding = kSimplifyBindingEdgeNeighbours, rgba32ui) uniform uimageBuffer edge_neighbours;
layout(binding = kSimplifyBindingVertexFirst, r32ui) uniform uimageBuffer vertex_first;
layout(binding = kSimplifyBindingValues, rgba32f) uniform readonly imageBuffer values;
layout(binding = kSimplifyBindingQuadrics, rg32ui) uniform uimageBuffer quadrics;
layout(binding = kSimplifyBindingPositions, rg32i) uniform iimageBuffer positions;

uvec4 verticesOf(uint e) { return imageLoad(edge_vertices, int(e)); }
uvec4 neighboursOf(uint e) { return imageLoad(edge_neighbours, int(e)); }
uint otherEnd(uvec4 v, uint p) { return v.x == p ? v.y : v.x; }

// core's turnAround: the edge after f around its endpoint v, counter-clockwise or clockwise.
uint turnAround(uint v, uint f, bool counter_clockwise) {
    const uvec4 n = neighboursOf(f);
    if (verticesOf(f).x == v) return counter_clockwise ? n.y : n.z;
    return counter_clockwise ? n.w : n.x;
}

// A walk over the edges at a vertex: `for (Walk w = beginWalk(v); w.f != kNone; advance(w))`
// visits them counter-clockwise from the vertex's first edge, then, where that meets the
// hull, clockwise from it.
struct Walk {
    uint v, start, f;
    bool forward;
};
Walk beginWalk(uint v) {
    const uint start = imageLoad(vertex_first, int(v)).x;
    return Walk(v, start, start, true);
}
void advance(inout Walk w) {
    uint next = turnAround(w.v, w.f, w.forward);
    if (w.forward) {
        if (next == w.start) next = kNone;
        else if (next == kNone) {
            w.forward = false;
            next = turnAround(w.v, w.start, false);
        }
    }
    w.f = next;
}

// 1 for the vertices whose edges the last round's collapses changed (collapse_edges.comp).
layout(binding = kSimplifyBindingChanged, r32ui) uniform uimageBuffer changed;

layout(binding = kSimplifyBindingListed, r32ui) uniform uimageBuffer listed;

// The edge this invocation works on (push.listed: the listed one), or kNone past the end.
uint invocationEdge() {
    const uint i = push.first_edge + gl_GlobalInvocationID.x;
    if (i >= push.edge_count) return kNone;
    return push.listed != 0u ? imageLoad(listed, int(i)).x : i;
}

ivec2 positionOf(uint v) { return imageLoad(positions, int(v)).xy; }

// core's collapseSides: rectangleSides' bits (0 x = 0, 1 x = w − 1, 2 y = 0, 3 y = h − 1),
// and bit 4 where one of them is locked.
uint sidesAt(ivec2 p) {
    const int right = int(push.width - 1u) * kPositionOne, bottom = int(push.height - 1u) * kPositionOne;
    const uint sides = uint(p.x == 0) | uint(p.x == right) << 1 | uint(p.y == 0) << 2 | uint(p.y == bottom) << 3;
    return (sides & push.locked_sides) != 0u ? sides | 16u : sides;
}
uint sidesOf(uint v) { return sidesAt(positionOf(v)); }

// core's hullPlaceOf: where v lies on the mesh's hull.
const uint kHullInside = 0u;
const uint kHullStraight = 1u;
const uint kHullCorner = 2u;
uint hullPlaceOf(uint v) {
    uint ends[2];
    uint count = 0u;
    for (Walk w = beginWalk(v); w.f != kNone; advance(w)) {
        const uvec4 fv = verticesOf(w.f);
        if ((fv.z == kNone || fv.w == kNone) && count < 2u) ends[count++] = otherEnd(fv, v);
    }
    if (count < 2u) return kHullInside;
    const ivec2 p = positionOf(ends[0]), q = positionOf(v), r = positionOf(ends[1]);
    return positionOrient(p.x, p.y, q.x, q.y, r.x, r.y) == 0l ? kHullStraight : kHullCorner;
}
// A merged vertex at v may move: v is inside, or on a straight stretch of the hull along a
// side of the rectangle.
bool movesOnHull(uint v, uint place) {
    return place == kHullInside || (place == kHullStraight && (sidesOf(v) & 15u) != 0u);
}

// Whether every triangle around `centre` but e's own (those holding `other`) stays positive
// with `from` and `to` at `target`.
bool staysPositive(uint e, uint centre, uint other, uint from, uint to, ivec2 target) {
    for (Walk w = beginWalk(centre); w.f != kNone; advance(w)) {
        if (w.f == e) continue;
        const uvec4 fv = verticesOf(w.f);
        for (uint side = 0u; side < 2u; ++side) {
            const uint p = side == 0u ? fv.x : fv.y, q = side == 0u ? fv.y : fv.x, r = side == 0u ? fv.z : fv.w;
            if (r == kNone || p == other || q == other || r == other) continue;
            const ivec2 a = p == from || p == to ? target : positionOf(p);
            const ivec2 b = q == from || q == to ? target : positionOf(q);
            const ivec2 c = r == from || r == to ? target : positionOf(r);
            if (positionOrient(a.x, a.y, b.x, b.y, c.x, c.y) <= 0l) return false;
        }
    }
    return true;
}

// core's canCollapse for edge e, in two parts: what holds for both directions (the valence
// bound and the link condition), then what depends on the direction.
bool eitherWayLegal(uint e) {
    const uvec4 ev = verticesOf(e);
    // b's neighbours, listed once (at most kMaxEdgesAtFrom where the valence bound holds), so
    // that the link condition's pairs compare registers rather than walk b's edges again.
    uint at_b[kMaxEdgesAtFrom];
    uint b_count = 0u, valence = 0u;
    for (Walk w = beginWalk(ev.y); w.f != kNone; advance(w)) {
        if (b_count < kMaxEdgesAtFrom) at_b[b_count] = otherEnd(verticesOf(w.f), ev.y);
        ++b_count;
    }
    for (Walk w = beginWalk(ev.x); w.f != kNone; advance(w)) ++valence;
    valence += b_count;
    if (valence - 2u - uint(ev.z != kNone) - uint(ev.w != kNone) > kCollapseValenceBound) return false;
    // Link condition: the common neighbours of a and b are e's adjacent vertices.
    uint shared_neighbours = 0u;
    for (Walk w = beginWalk(ev.x); w.f != kNone; advance(w)) {
        const uint x = otherEnd(verticesOf(w.f), ev.x);
        if (x == ev.y) continue;
        for (uint i = 0u; i < b_count; ++i) {
            if (at_b[i] != x) continue;
            if (x != ev.z && x != ev.w) return false;
            ++shared_neighbours;
        }
    }
    return shared_neighbours == uint(ev.z != kNone) + uint(ev.w != kNone);
}

// The rest of core's canCollapse, `from` e's endpoint b (b_into_a) or a: the rectangle kept,
// no fold-over, with the merged vertex at `to`'s place or, if it `moves`, at `target`.
bool directionLegal(uint e, bool b_into_a, bool moves, ivec2 target) {
    const uvec4 ev = verticesOf(e);
    const uint from = b_into_a ? ev.y : ev.x, to = b_into_a ? ev.x : ev.y;
    const uint from_sides = sidesOf(from);
    if (bitCount(from_sides) >= 2) return false;  // a corner
    const uint from_hull = hullPlaceOf(from);
    if (from_hull == kHullCorner) return false;                                     // the hull would lose it
    if (from_hull != kHullInside && ev.z != kNone && ev.w != kNone) return false;  // a hull vertex leaves the hull
    if (moves) {
        const uint kept = from_sides | sidesOf(to);
        if ((sidesAt(target) & kept) != kept) return false;
        if (!movesOnHull(from, from_hull) || !movesOnHull(to, hullPlaceOf(to))) return false;
    } else {
        target = positionOf(to);
    }
    return staysPositive(e, from, to, from, to, target) && (!moves || staysPositive(e, to, from, from, to, target));
}

double quadricWord(uint v, uint k) { return packDouble2x32(imageLoad(quadrics, int(v * kQuadricDoubles + k)).xy); }

// The sum of two vertices' quadrics, the entries that 2 + push.channels coordinates use (the
// rest stay 0): both directions of a collapse cost this sum, since addition commutes.
struct QuadricSum {
    double a[kQuadricUpperSize];
    double b[kMaxQuadricDimensions];
    double c;
    double area;
};
QuadricSum quadricSum(uint p, uint q) {
    QuadricSum sum;
    const uint n = 2u + push.channels;
    for (uint i = 0u; i < kMaxQuadricDimensions; ++i) {
        for (uint j = i; j < kMaxQuadricDimensions; ++j) {
            const uint k = quadricIndex(i, j);
            sum.a[k] = j < n ? quadricWord(p, k) + quadricWord(q, k) : 0.0lf;
        }
        sum.b[i] = i < n ? quadricWord(p, kQuadricUpperSize + i) + quadricWord(q, kQuadricUpperSize + i) : 0.0lf;
    }
    sum.c = quadricWord(p, kQuadricUpperSize + kMaxQuadricDimensions) +
            quadricWord(q, kQuadricUpperSize + kMaxQuadricDimensions);
    sum.area = quadricWord(p, kQuadricUpperSize + kMaxQuadricDimensions + 1u) +
               quadricWord(q, kQuadricUpperSize + kMaxQuadricDimensions + 1u);
    return sum;
}

// A of the sum at (i, j), either way round.
double entry(QuadricSum sum, uint i, uint j) { return sum.a[i <= j ? quadricIndex(i, j) : quadricIndex(j, i)]; }

// core's Quadric::minimiseFree: the coordinates of v whose bits are set in `free` that minimise
// the sum with the others given; false (v unchanged) where that block is singular.
bool minimiseFree(QuadricSum sum, inout double v[kMaxQuadricDimensions], uint free, uint n) {
    uint index[kMaxQuadricDimensions];
    uint m = 0u;
    for (uint k = 0u; k < n; ++k)
        if ((free >> k & 1u) != 0u) index[m++] = k;
    precise double system[kMaxQuadricDimensions][kMaxQuadricDimensions + 1u];
    for (uint i = 0u; i < m; ++i) {
        precise double rhs = -sum.b[index[i]];
        for (uint k = 0u; k < n; ++k)
            if ((free >> k & 1u) == 0u) rhs -= entry(sum, index[i], k) * v[k];
        for (uint j = 0u; j < m; ++j) system[i][j] = entry(sum, index[i], index[j]);
        system[i][m] = rhs;
    }
    for (uint col = 0u; col < m; ++col) {
        uint pivot = col;
        for (uint r = col + 1u; r < m; ++r)
            if (abs(system[r][col]) > abs(system[pivot][col])) pivot = r;
        if (abs(system[pivot][col]) < 1e-12lf) return false;
        for (uint j = 0u; j <= m; ++j) {
            const double swapped = system[col][j];
            system[col][j] = system[pivot][j];
            system[pivot][j] = swapped;
        }
        for (uint r = col + 1u; r < m; ++r) {
            precise double factor = system[r][col] / system[col][col];
            for (uint j = col; j <= m; ++j) system[r][j] -= factor * system[col][j];
        }
    }
    precise double solution[kMaxQuadricDimensions];
    for (uint i = m; i-- > 0u;) {
        precise double total = system[i][m];
        for (uint j = i + 1u; j < m; ++j) total -= system[i][j] * solution[j];
        solution[i] = total / system[i][i];
    }
    for (uint i = 0u; i < m; ++i) v[index[i]] = solution[i];
    return true;
}

// core's QuadricPoints::at: a point's position coordinates for position p.
void setPosition(ivec2 p, inout double point[kMaxQuadricDimensions]) {
    precise double x = kPositionWeight * double(p.x), y = kPositionWeight * double(p.y);
    point[0] = x / double(kPositionOne);
    point[1] = y / double(kPositionOne);
}

// core's QuadricPoints::of: vertex v's colour with position p.
void pointAt(ivec2 p, uint v, out double point[kMaxQuadricDimensions]) {
    for (uint k = 0u; k < kMaxQuadricDimensions; ++k) point[k] = 0.0lf;
    setPosition(p, point);
    const vec4 value = imageLoad(values, int(v));
    for (uint k = 0u; k < push.channels; ++k) point[2u + k] = double(value[k]);
}

// core's costAt: the sum at position p with the colour that is best there (v's own if the
// colour block is singular).
double costAt(QuadricSum sum, ivec2 p, uint v) {
    double point[kMaxQuadricDimensions];
    pointAt(p, v, point);
    const uint n = 2u + push.channels;
    minimiseFree(sum, point, ((1u << n) - 1u) & ~3u, n);
    return quadricValue(sum.a, sum.b, sum.c, point, n);
}

// core's snapped: a point's position coordinate on the fixed-point grid, −1 if not finite or
// off the rectangle's [0, side − 1].
int snapped(double coordinate, uint side) {
    precise double scaled = coordinate / kPositionWeight;
    precise double grid = roundEven(scaled * double(kPositionOne));
    if (!(grid >= 0.0lf && grid <= double(side - 1u) * double(kPositionOne))) return -1;
    return int(grid);
}

// A collapse's place and cost (core's PlacedCollapse).
struct Placed {
    bool moves;
    ivec2 target;
    double cost;
};

// core's moveTo: the least point of the sum with the axes `free` (the others `to`'s), snapped,
// if legal and not `to`'s place, with its cost; moves = false otherwise.
Placed moveTo(QuadricSum sum, uint e, bool b_into_a, uint free) {
    const uvec4 ev = verticesOf(e);
    const uint to = b_into_a ? ev.x : ev.y, n = 2u + push.channels;
    const Placed none = Placed(false, ivec2(0), 0.0lf);
    const ivec2 at_to = positionOf(to);
    double point[kMaxQuadricDimensions];
    pointAt(at_to, to, point);
    if (!minimiseFree(sum, point, free, n)) return none;
    const int x = snapped(point[0], push.width), y = snapped(point[1], push.height);
    if (x < 0 || y < 0) return none;
    const ivec2 target = ivec2(x, y);
    if (target == at_to || !directionLegal(e, b_into_a, true, target)) return none;
    setPosition(target, point);
    if (!minimiseFree(sum, point, ((1u << n) - 1u) & ~3u, n)) return none;
    return Placed(true, target, quadricValue(sum.a, sum.b, sum.c, point, n));
}

// core's placeCollapses, the mesh's positions explicit: e's collapses placed, [0] a into b,
// [1] b into a (their legality at `to`'s place not checked).
void placeCollapses(QuadricSum sum, uint e, out Placed placed[2]) {
    const uvec4 ev = verticesOf(e);
    const uint sides[2] = uint[2](sidesOf(ev.x), sidesOf(ev.y));
    const uint all = (1u << (2u + push.channels)) - 1u;
    Placed inside = Placed(false, ivec2(0), 0.0lf);
    if (sides[0] == 0u && sides[1] == 0u) inside = moveTo(sum, e, true, all);
    for (uint direction = 0u; direction < 2u; ++direction) {
        const uint from_sides = sides[direction], to_sides = sides[1u - direction];
        const uint to = direction == 1u ? ev.x : ev.y;
        const ivec2 at_to = positionOf(to);
        const Placed stays = Placed(false, at_to, costAt(sum, at_to, to));
        Placed moved = Placed(false, ivec2(0), 0.0lf);
        if (inside.moves) moved = inside;
        else if (bitCount(to_sides) == 1 && (from_sides == 0u || from_sides == to_sides))
            moved = moveTo(sum, e, direction == 1u, all & ((to_sides & 3u) != 0u ? ~1u : ~2u));
        placed[direction] = moved.moves && moved.cost <= stays.cost ? moved : stays;
    }
}
