// The sweep: points taken in row-major order, each joined to the hull of those before it.
//
// Why it works: the newest point p_k is greater (row-major) than every point before it, so it
// lies strictly outside their closed hull, and the previous point p_(k−1), the hull's greatest,
// is a hull vertex that p_k sees (the segment between them stays at or beyond p_(k−1)'s row).
// The hull near p_(k−1) lies in the cone of its two hull edges, whose directions are both
// smaller row-major, so every point of that cone is too: p_k is outside it, and at least one
// of the two hull edges at p_(k−1) faces it strictly. The hull edges p_k sees strictly form
// one chain through p_(k−1); walking it both ways from there adds one triangle per edge and
// ends at the first edge that does not face p_k (collinear ones included, so points on the
// hull's sides stay vertices). Every step past the first of each walk removes a hull vertex
// for good: O(n) in all.
//
// The hull is a ring of vertices in positive order (core/mesh.h: the inside on the left of
// each hull edge v → next), with the id of the edge v → next.
#include "sweep_triangulation.h"

#include <cassert>

#include "predicates.h"

namespace ddt {

namespace {

class Sweep {
public:
    Sweep(uint32_t width, uint32_t height, const std::vector<Position>& points)
        : points_(points), next_(points.size()), previous_(points.size()), hull_edge_(points.size()) {
        mesh_.width = width;
        mesh_.height = height;
        // A triangulation of n points with h on the hull has 3n − 3 − h edges.
        mesh_.vertices.reserve(3 * points.size());
        mesh_.neighbours.reserve(3 * points.size());
    }

    Mesh run();

private:
    int64_t orientOf(uint32_t p, uint32_t q, uint32_t r) const { return orient(points_[p], points_[q], points_[r]); }
    uint32_t newEdge(uint32_t p, uint32_t q);
    void attachSide(uint32_t g, uint32_t x, uint32_t z, uint32_t e_yz, uint32_t e_zx);
    void attachTriangle(uint32_t x, uint32_t y, uint32_t z, uint32_t e_xy, uint32_t e_yz, uint32_t e_zx);
    void link(uint32_t v, uint32_t next, uint32_t edge) {
        next_[v] = next;
        previous_[next] = v;
        hull_edge_[v] = edge;
    }
    uint32_t startWithFan();
    void addPoint(uint32_t p);

    const std::vector<Position>& points_;
    Mesh mesh_;
    std::vector<uint32_t> next_, previous_, hull_edge_;  // the hull ring, per vertex on it
};

uint32_t Sweep::newEdge(uint32_t p, uint32_t q) {
    mesh_.vertices.push_back({p, q, kNone, kNone});
    mesh_.neighbours.push_back({kNone, kNone, kNone, kNone});
    return mesh_.edgeCount() - 1;
}

// The positive triangle (x, y, z) on edge g = x–y, whose other edges are e_yz and e_zx: g's
// left side if g runs x → y, else its right (core/mesh.h's record order either way).
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
// Returns m.
uint32_t Sweep::startWithFan() {
    const uint32_t n = uint32_t(points_.size());
    uint32_t m = 2;
    while (m < n && orientOf(0, 1, m) == 0) ++m;
    assert(m < n);  // not all collinear
    std::vector<uint32_t> chain(m - 1), spoke(m);
    for (uint32_t i = 0; i + 1 < m; ++i) chain[i] = newEdge(i, i + 1);
    for (uint32_t i = 0; i < m; ++i) spoke[i] = newEdge(i, m);
    if (orientOf(0, 1, m) > 0) {
        // Triangles (i, i + 1, m); hull 0 → 1 → … → m − 1 → m → 0.
        for (uint32_t i = 0; i + 1 < m; ++i) {
            attachTriangle(i, i + 1, m, chain[i], spoke[i + 1], spoke[i]);
            link(i, i + 1, chain[i]);
        }
        link(m - 1, m, spoke[m - 1]);
        link(m, 0, spoke[0]);
    } else {
        // Triangles (i + 1, i, m); hull m − 1 → … → 1 → 0 → m → m − 1.
        for (uint32_t i = 0; i + 1 < m; ++i) {
            attachTriangle(i + 1, i, m, chain[i], spoke[i], spoke[i + 1]);
            link(i + 1, i, chain[i]);
        }
        link(0, m, spoke[0]);
        link(m, m - 1, spoke[m - 1]);
    }
    return m;
}

// Joins p to the hull edges it strictly faces, walking both ways from the previous point.
void Sweep::addPoint(uint32_t p) {
    const uint32_t last = p - 1;
    const uint32_t last_spoke = newEdge(last, p);
    uint32_t v = last, v_spoke = last_spoke;  // forwards: edges v → w
    while (orientOf(v, next_[v], p) < 0) {
        const uint32_t w = next_[v], w_spoke = newEdge(w, p);
        attachTriangle(w, v, p, hull_edge_[v], v_spoke, w_spoke);
        v = w;
        v_spoke = w_spoke;
    }
    uint32_t u = last, u_spoke = last_spoke;  // backwards: edges t → u
    while (orientOf(previous_[u], u, p) < 0) {
        const uint32_t t = previous_[u], t_spoke = newEdge(t, p);
        attachTriangle(u, t, p, hull_edge_[t], t_spoke, u_spoke);
        u = t;
        u_spoke = t_spoke;
    }
    assert(u != last || v != last);  // it faced at least one edge
    link(u, p, u_spoke);
    link(p, v, v_spoke);
}

Mesh Sweep::run() {
    const uint32_t n = uint32_t(points_.size());
    for (uint32_t p = startWithFan() + 1; p < n; ++p) addPoint(p);
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
