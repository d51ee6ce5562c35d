// The sweep: points taken in row-major order (rows of increasing y), each joined to an
// advancing front, the upper side of the triangulated region, as Žalik's sweep-line
// triangulation does; at the end the front's pockets are filled so the region is the hull.
//
// The region's boundary is a ring of vertices in positive order (core/image/mesh.h: the inside on
// the left of each edge v → next), with the id of the edge v → next. Two of its vertices
// split it: L, the leftmost point (the highest of those), and R, the rightmost (likewise).
// From R the ring runs to L along the front, whose x never grows, and from L back to R along
// the region's lower convex hull, which no later point can see from below.
//
// Why every triangle is new ground: each point p lies row-major after every point before it,
// so at or above all of them. Where L.x ≤ p.x < R.x, p is above the front edge under it (the
// edge's height at p.x is at most its higher end's, and equal only for a point that would come
// after p), and the triangle of p and that edge lies between the front and p, where nothing
// is yet. The walks then add a triangle (p, r, r1) only where r is below the segment p–r1, so
// the triangle again lies between the front (p → r → r1, x-monotone) and that segment. Where
// p is beyond L or R it is outside the hull of the points before it (it is their row-major
// greatest) and joins the edges it sees; those on the lower hull are outside the hull, those
// on the front above the front, and from p each group turns one way round the ray to the
// extreme point, less than a half-turn in all. The walks never pass L or R, so both stay the
// extremes and the front stays x-monotone.
//
// Why the triangles are not long and thin: a point joins only the front edge under it, and
// the walks add the triangles of neighbouring front edges only while the angle at the front
// vertex they remove is below a right angle (Žalik's rule). That keeps the front close to the
// points, and the mesh close to Delaunay, so the flips that follow have little to do. The
// first two rows, when the first is a row of several points, are zipped together, cell by
// cell, so a pixel grid starts with no fan at all.
//
// Finding the front edge over p: a short walk from a front vertex near p in x, the one last
// inserted in p's bucket of x (√n buckets) or the one that removed it from the front, or the
// nearest bucket's such.
#include "sweep_triangulation.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

#include "predicates.h"

namespace ddt {

namespace {

class Sweep {
public:
    Sweep(uint32_t width, uint32_t height, const std::vector<Position>& points)
        : points_(points), next_(points.size()), previous_(points.size()), hull_edge_(points.size()) {
        mesh_.width = width;
        mesh_.height = height;
        mesh_.hull = MeshHull::convex;
        // A triangulation of n points with h on the hull has 3n − 3 − h edges.
        mesh_.vertices.reserve(3 * points.size());
        mesh_.neighbours.reserve(3 * points.size());
        int32_t low = points[0].x, high = points[0].x;
        for (const Position& p : points) {
            low = std::min(low, p.x);
            high = std::max(high, p.x);
        }
        bucket_low_ = low;
        bucket_span_ = int64_t(high) - low + 1;
        hint_.assign(size_t(std::ceil(std::sqrt(double(points.size())))), kNone);
        on_front_.assign(points.size(), false);
    }

    Mesh run();

private:
    const Position& at(uint32_t v) const { return points_[v]; }
    int64_t orientOf(uint32_t p, uint32_t q, uint32_t r) const { return orient(at(p), at(q), at(r)); }
    // Whether the angle at v between p and w is below a right angle.
    bool acuteAt(uint32_t v, uint32_t p, uint32_t w) const {
        return (int64_t(at(p).x) - at(v).x) * (int64_t(at(w).x) - at(v).x) +
                   (int64_t(at(p).y) - at(v).y) * (int64_t(at(w).y) - at(v).y) >
               0;
    }
    size_t bucketOf(uint32_t v) const {
        return size_t((int64_t(at(v).x) - bucket_low_) * int64_t(hint_.size()) / bucket_span_);
    }

    uint32_t newEdge(uint32_t p, uint32_t q);
    void attachSide(uint32_t g, uint32_t x, uint32_t z, uint32_t e_yz, uint32_t e_zx);
    void attachTriangle(uint32_t x, uint32_t y, uint32_t z, uint32_t e_xy, uint32_t e_yz, uint32_t e_zx);
    void link(uint32_t v, uint32_t next, uint32_t edge) {
        next_[v] = next;
        previous_[next] = v;
        hull_edge_[v] = edge;
    }
    // v has left the front; a hint to it in its own bucket moves to p, which is on the front.
    void leaveFront(uint32_t v, uint32_t p) {
        on_front_[v] = false;
        uint32_t& hint = hint_[bucketOf(v)];
        if (hint == v) hint = p;
    }

    uint32_t startWithFan();
    uint32_t startWithTwoRows();
    void findEnds(uint32_t started);
    void addPoint(uint32_t p);
    void addAboveFront(uint32_t p);
    void addBeyondRight(uint32_t p);
    void addBeyondLeft(uint32_t p);
    uint32_t nearbyFrontVertex(uint32_t p) const;
    uint32_t frontVertexAtOrLeftOf(uint32_t p) const;
    void joinToEdgeBefore(uint32_t p, uint32_t v);
    void joinToEdgeAfter(uint32_t p, uint32_t v);
    void walkRight(uint32_t p, uint32_t stop, bool acute_only);
    void walkLeft(uint32_t p, uint32_t stop, bool acute_only);
    void fillFront();

    const std::vector<Position>& points_;
    Mesh mesh_;
    std::vector<uint32_t> next_, previous_, hull_edge_;  // the ring, per vertex on it
    uint32_t left_ = kNone, right_ = kNone;             // L and R
    std::vector<uint32_t> hint_;                         // per bucket of x: a vertex, or kNone
    std::vector<uint8_t> on_front_;                      // per vertex
    int32_t bucket_low_ = 0;
    int64_t bucket_span_ = 1;
};

uint32_t Sweep::newEdge(uint32_t p, uint32_t q) {
    mesh_.vertices.push_back({p, q, kNone, kNone});
    mesh_.neighbours.push_back({kNone, kNone, kNone, kNone});
    return mesh_.edgeCount() - 1;
}

// The positive triangle (x, y, z) on edge g = x–y, whose other edges are e_yz and e_zx: g's
// left side if g runs x → y, else its right (core/image/mesh.h's record order either way).
void Sweep::attachSide(uint32_t g, uint32_t x, uint32_t z, uint32_t e_yz, uint32_t e_zx) {
    EdgeVertices& v = mesh_.vertices[g];
    EdgeNeighbours& n = mesh_.neighbours[g];
    if (v.a == x) {
        v.l = z;
        n.bl = e_yz;
        n.la = e_zx;
    } else {
        v.r = z;
        n.ar = e_yz;
        n.rb = e_zx;
    }
}

void Sweep::attachTriangle(uint32_t x, uint32_t y, uint32_t z, uint32_t e_xy, uint32_t e_yz, uint32_t e_zx) {
    assert(orientOf(x, y, z) > 0);
    attachSide(e_xy, x, z, e_yz, e_zx);
    attachSide(e_yz, y, x, e_zx, e_xy);
    attachSide(e_zx, z, y, e_xy, e_yz);
}

// The first points up to the first one off their line, m: the collinear ones in a chain
// (row-major order is their order along the line), each chain edge in a triangle with m.
// Returns how many points it took, m + 1.
uint32_t Sweep::startWithFan() {
    const uint32_t n = uint32_t(points_.size());
    uint32_t m = 2;
    while (m < n && orientOf(0, 1, m) == 0) ++m;
    assert(m < n);  // not all collinear
    std::vector<uint32_t> chain(m - 1), spoke(m);
    for (uint32_t i = 0; i + 1 < m; ++i) chain[i] = newEdge(i, i + 1);
    for (uint32_t i = 0; i < m; ++i) spoke[i] = newEdge(i, m);
    if (orientOf(0, 1, m) > 0) {
        // Triangles (i, i + 1, m); ring 0 → 1 → … → m − 1 → m → 0.
        for (uint32_t i = 0; i + 1 < m; ++i) {
            attachTriangle(i, i + 1, m, chain[i], spoke[i + 1], spoke[i]);
            link(i, i + 1, chain[i]);
        }
        link(m - 1, m, spoke[m - 1]);
        link(m, 0, spoke[0]);
    } else {
        // Triangles (i + 1, i, m); ring m − 1 → … → 1 → 0 → m → m − 1.
        for (uint32_t i = 0; i + 1 < m; ++i) {
            attachTriangle(i + 1, i, m, chain[i], spoke[i], spoke[i + 1]);
            link(i + 1, i, chain[i]);
        }
        link(0, m, spoke[0]);
        link(m, m - 1, spoke[m - 1]);
    }
    return m + 1;
}

// The first row a (two points or more) and the second b, zipped into the strip between them
// in order of x. At equal x the step along b comes first, so a unit grid cell is cut by
// (x, y)–(x + 1, y + 1), as the Delaunay tie-break cuts it. Every triangle is positive
// whatever the x's: two points of one row and one of the other, the rows' order fixing the
// turn. Returns how many points it took.
uint32_t Sweep::startWithTwoRows() {
    const uint32_t n = uint32_t(points_.size());
    uint32_t a_end = 1;
    while (points_[a_end].y == points_[0].y) ++a_end;  // not all collinear: a row follows
    uint32_t b_end = a_end + 1;
    while (b_end < n && points_[b_end].y == points_[a_end].y) ++b_end;
    for (uint32_t i = 0; i + 1 < a_end; ++i) link(i, i + 1, newEdge(i, i + 1));
    for (uint32_t j = a_end; j + 1 < b_end; ++j) link(j + 1, j, newEdge(j, j + 1));
    uint32_t a = 0, b = a_end, rung = newEdge(a, b);
    link(b, a, rung);
    while (a + 1 < a_end || b + 1 < b_end) {
        const bool along_b = b + 1 < b_end && (a + 1 == a_end || points_[b + 1].x <= points_[a + 1].x);
        if (along_b) {
            const uint32_t next_rung = newEdge(a, b + 1);
            attachTriangle(a, b + 1, b, next_rung, hull_edge_[b + 1], rung);
            ++b;
            rung = next_rung;
        } else {
            const uint32_t next_rung = newEdge(a + 1, b);
            attachTriangle(a, a + 1, b, hull_edge_[a], next_rung, rung);
            ++a;
            rung = next_rung;
        }
    }
    link(a, b, rung);
    return b_end;
}

// L and R among the first `started` points, all on the ring; the front's vertices as hints.
void Sweep::findEnds(uint32_t started) {
    left_ = right_ = 0;
    for (uint32_t v = 1; v < started; ++v) {
        // Row-major order: a later point at the same x is higher.
        if (at(v).x <= at(left_).x) left_ = v;
        if (at(v).x >= at(right_).x) right_ = v;
    }
    for (uint32_t v = right_;; v = next_[v]) {
        hint_[bucketOf(v)] = v;
        on_front_[v] = true;
        if (v == left_) break;
    }
}

void Sweep::addPoint(uint32_t p) {
    if (at(p).x < at(left_).x)
        addBeyondLeft(p);
    else if (at(p).x >= at(right_).x)
        addBeyondRight(p);
    else
        addAboveFront(p);
    hint_[bucketOf(p)] = p;
    on_front_[p] = true;
}

// A front vertex near p in x: the hint of p's bucket or else of the nearest bucket either side
// whose hint is still on the front. There is one: the previous point is still its bucket's hint
// (or, just after the start, that bucket holds another front vertex).
uint32_t Sweep::nearbyFrontVertex(uint32_t p) const {
    const size_t bucket = bucketOf(p), buckets = hint_.size();
    for (size_t distance = 0;; ++distance) {
        assert(distance < buckets);
        for (const size_t b : {bucket - distance, bucket + distance}) {  // wraps past 0: too large
            if (b >= buckets) continue;
            const uint32_t v = hint_[b];
            if (v != kNone && on_front_[v]) return v;
        }
    }
}

// The front vertex l with l.x ≤ p.x < r.x for r = previous_[l] (the first from R at or left
// of p), found by walking from a hint. Needs L.x ≤ p.x < R.x.
uint32_t Sweep::frontVertexAtOrLeftOf(uint32_t p) const {
    const int32_t x = at(p).x;
    uint32_t v = nearbyFrontVertex(p);
    if (at(v).x <= x) {
        while (at(previous_[v]).x <= x) v = previous_[v];
    } else {
        while (at(v).x > x) v = next_[v];
    }
    return v;
}

// p joins the ring on the edge u → v (u = previous_[v]): ring u → p → v.
void Sweep::joinToEdgeBefore(uint32_t p, uint32_t v) {
    const uint32_t u = previous_[v], e_up = newEdge(u, p), e_pv = newEdge(p, v);
    attachTriangle(v, u, p, hull_edge_[u], e_up, e_pv);
    link(u, p, e_up);
    link(p, v, e_pv);
}

// p joins the ring on the edge v → w (w = next_[v]): ring v → p → w.
void Sweep::joinToEdgeAfter(uint32_t p, uint32_t v) { joinToEdgeBefore(p, next_[v]); }

// Along the ring before p (r = previous_[p], r1 = previous_[r]): the triangle (r, r1, p)
// while p sees r1 → r, r is not `stop`, and (if acute_only) the angle at r is acute.
void Sweep::walkRight(uint32_t p, uint32_t stop, bool acute_only) {
    for (uint32_t r = previous_[p]; r != stop; r = previous_[p]) {
        const uint32_t r1 = previous_[r];
        if (orientOf(r, r1, p) <= 0 || (acute_only && !acuteAt(r, p, r1))) break;
        const uint32_t e = newEdge(r1, p);
        attachTriangle(r, r1, p, hull_edge_[r1], e, hull_edge_[r]);
        link(r1, p, e);
        leaveFront(r, p);
    }
}

// Along the ring after p (l = next_[p], l1 = next_[l]): the triangle (l1, l, p) while p
// sees l → l1, l is not `stop`, and (if acute_only) the angle at l is acute.
void Sweep::walkLeft(uint32_t p, uint32_t stop, bool acute_only) {
    for (uint32_t l = next_[p]; l != stop; l = next_[p]) {
        const uint32_t l1 = next_[l];
        if (orientOf(l1, l, p) <= 0 || (acute_only && !acuteAt(l, p, l1))) break;
        const uint32_t e = newEdge(p, l1);
        attachTriangle(l1, l, p, hull_edge_[l], hull_edge_[p], e);
        link(p, l1, e);
        leaveFront(l, p);
    }
}

// L.x ≤ p.x < R.x: p on the front edge over it, then the acute walks both ways. A point right
// above L becomes L (L's next walk stops at once: next_[p] is L).
void Sweep::addAboveFront(uint32_t p) {
    const uint32_t l = frontVertexAtOrLeftOf(p);
    joinToEdgeBefore(p, l);
    walkRight(p, right_, true);
    walkLeft(p, left_, true);
    if (at(p).x == at(left_).x) {
        leaveFront(left_, p);
        left_ = p;
    }
}

// p.x ≥ R.x: p joins the first front edge from R if it sees it, else the lower hull's last;
// then the front walk (acute) and the lower hull's (every edge p sees), both stopping at L.
void Sweep::addBeyondRight(uint32_t p) {
    const uint32_t r = right_;
    if (orientOf(r, next_[r], p) < 0)
        joinToEdgeAfter(p, r);
    else
        joinToEdgeBefore(p, r);
    walkLeft(p, left_, true);
    walkRight(p, left_, false);
    if (next_[p] != r) leaveFront(r, p);
    right_ = p;
}

// p.x < L.x: the mirror image, the walks stopping at R.
void Sweep::addBeyondLeft(uint32_t p) {
    const uint32_t l = left_;
    if (orientOf(previous_[l], l, p) < 0)
        joinToEdgeBefore(p, l);
    else
        joinToEdgeAfter(p, l);
    walkRight(p, right_, true);
    walkLeft(p, right_, false);
    if (previous_[p] != l) leaveFront(l, p);
    left_ = p;
}

// The front's pockets filled from L to R: b, between a (towards L) and c, is dropped while
// it turns the front the wrong way, then a is checked again. After this the ring is convex
// (collinear vertices kept: the tests are strict).
void Sweep::fillFront() {
    uint32_t a = left_, b = previous_[a];
    while (b != right_) {
        const uint32_t c = previous_[b];
        if (orientOf(a, b, c) > 0) {
            const uint32_t e = newEdge(c, a);
            attachTriangle(a, b, c, hull_edge_[b], hull_edge_[c], e);
            link(c, a, e);
            if (a != left_) {
                b = a;
                a = next_[a];
            } else {
                b = c;
            }
        } else {
            a = b;
            b = c;
        }
    }
}

Mesh Sweep::run() {
    const uint32_t n = uint32_t(points_.size());
    const bool first_row_has_two = points_[1].y == points_[0].y;
    const uint32_t started = first_row_has_two ? startWithTwoRows() : startWithFan();
    findEnds(started);
    for (uint32_t p = started; p < n; ++p) addPoint(p);
    fillFront();
    mesh_.positions = points_;
    return std::move(mesh_);
}

}  // namespace

Mesh sweepTriangulation(uint32_t width, uint32_t height, const std::vector<Position>& points) {
    assert(points.size() >= 3);
#ifndef NDEBUG
    for (size_t i = 1; i < points.size(); ++i)
        assert(points[i - 1].y < points[i].y || (points[i - 1].y == points[i].y && points[i - 1].x < points[i].x));
#endif
    return Sweep(width, height, points).run();
}

}  // namespace ddt
