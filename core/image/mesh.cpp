#include "mesh.h"

#include <algorithm>
#include <cassert>
#include <sstream>
#include <unordered_map>

namespace ddt {

namespace {

// Edge ids of the initial grid (see mesh.h): row y < h−1 holds, per vertex, right, down and
// diagonal (the last column only down): 3w − 2 edges; the last row holds w − 1 right edges.
struct GridEdgeIds {
    uint32_t width, height;

    uint32_t rowBase(uint32_t y) const { return y * (3 * width - 2); }
    uint32_t right(uint32_t x, uint32_t y) const {
        return y + 1 < height ? rowBase(y) + 3 * x : rowBase(y) + x;
    }
    uint32_t down(uint32_t x, uint32_t y) const { return rowBase(y) + 3 * x + (x + 1 < width ? 1 : 0); }
    uint32_t diagonal(uint32_t x, uint32_t y) const { return rowBase(y) + 3 * x + 2; }
};

// Records the positive triangle (p, q, t) on the side of edge pq (id e_pq) where it lies;
// e_qt and e_tp are its other two edges.
void attachTriangle(Mesh& mesh, uint32_t e_pq, uint32_t p, uint32_t t, uint32_t e_qt, uint32_t e_tp) {
    EdgeVertices& v = mesh.vertices[e_pq];
    EdgeNeighbours& n = mesh.neighbours[e_pq];
    if (v.a == p) {  // (a, b, t) is the left triangle
        v.l = t;
        n.bl = e_qt;
        n.la = e_tp;
    } else {  // (b, a, t) is the right triangle
        v.r = t;
        n.ar = e_qt;
        n.rb = e_tp;
    }
}

void attachTriangle3(Mesh& mesh, uint32_t p0, uint32_t p1, uint32_t p2, uint32_t e01, uint32_t e12, uint32_t e20) {
    attachTriangle(mesh, e01, p0, p2, e12, e20);
    attachTriangle(mesh, e12, p1, p0, e20, e01);
    attachTriangle(mesh, e20, p2, p1, e01, e12);
}

// After e's flip, the neighbour edge n (whose triangle with e had third vertex old_near) lies
// in a new triangle with third vertex new_near; the slot that held e now holds `successor`,
// the one that held the other old edge now holds e.
void patchNeighbour(Mesh& mesh, uint32_t n, uint32_t e, uint32_t old_near, uint32_t new_near, uint32_t successor) {
    if (n == kNone) return;
    EdgeVertices& v = mesh.vertices[n];
    EdgeNeighbours& nb = mesh.neighbours[n];
    uint32_t* slot0 = &nb.bl;
    uint32_t* slot1 = &nb.la;
    if (v.l == old_near) {
        v.l = new_near;
    } else {
        assert(v.r == old_near);
        v.r = new_near;
        slot0 = &nb.ar;
        slot1 = &nb.rb;
    }
    *slot0 = *slot0 == e ? successor : e;
    *slot1 = *slot1 == e ? successor : e;
}

// Whether p–q runs along one side of the rectangle (a unit step on the initial grid, longer
// once simplification removed border vertices between them).
bool onHullSide(const Mesh& mesh, uint32_t p, uint32_t q) {
    return (rectangleSides(mesh, p) & rectangleSides(mesh, q)) != 0 && positionOf(mesh, p) != positionOf(mesh, q);
}

bool joins(const EdgeVertices& v, uint32_t p, uint32_t q) {
    return (v.a == p && v.b == q) || (v.a == q && v.b == p);
}

}  // namespace

void makePositionsExplicit(Mesh& mesh) {
    assert(mesh.width <= kMaxPositionedSide && mesh.height <= kMaxPositionedSide);
    if (!mesh.positions.empty()) return;
    std::vector<Position> positions(mesh.vertexCount());
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) positions[v] = positionOf(mesh, v);
    mesh.positions = std::move(positions);
}

int orientationSign(const Mesh& mesh, uint32_t p, uint32_t q, uint32_t r) {
    const Position a = positionOf(mesh, p), b = positionOf(mesh, q), c = positionOf(mesh, r);
    const int64_t twice_area = positionOrient(a.x, a.y, b.x, b.y, c.x, c.y);
    return (twice_area > 0) - (twice_area < 0);
}

uint32_t rectangleSides(const Mesh& mesh, Position p) {
    const int32_t right = int32_t(mesh.width - 1) * kPositionOne, bottom = int32_t(mesh.height - 1) * kPositionOne;
    return uint32_t(p.x == 0) | uint32_t(p.x == right) << 1 | uint32_t(p.y == 0) << 2 | uint32_t(p.y == bottom) << 3;
}

uint64_t gridEdgeCount(uint32_t width, uint32_t height) {
    return uint64_t(height - 1) * (3 * uint64_t(width) - 2) + (width - 1);
}

Mesh buildGridMesh(uint32_t width, uint32_t height) {
    assert(width >= 2 && height >= 2);
    Mesh mesh;
    mesh.width = width;
    mesh.height = height;
    const uint64_t edge_count = gridEdgeCount(width, height);
    mesh.vertices.reserve(edge_count);
    const EdgeNeighbours no_neighbours = {kNone, kNone, kNone, kNone};
    mesh.neighbours.assign(edge_count, no_neighbours);

    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            uint32_t v = y * width + x;
            if (x + 1 < width) mesh.vertices.push_back({v, v + 1, kNone, kNone});
            if (y + 1 < height) mesh.vertices.push_back({v, v + width, kNone, kNone});
            if (x + 1 < width && y + 1 < height) mesh.vertices.push_back({v, v + width + 1, kNone, kNone});
        }
    }
    assert(mesh.vertices.size() == edge_count);

    const GridEdgeIds ids{width, height};
    for (uint32_t y = 0; y + 1 < height; ++y) {
        for (uint32_t x = 0; x + 1 < width; ++x) {
            uint32_t p00 = y * width + x, p10 = p00 + 1, p01 = p00 + width, p11 = p01 + 1;
            // Upper-right triangle (p00, p10, p11) and lower-left (p00, p11, p01), both positive.
            attachTriangle3(mesh, p00, p10, p11, ids.right(x, y), ids.down(x + 1, y), ids.diagonal(x, y));
            attachTriangle3(mesh, p00, p11, p01, ids.diagonal(x, y), ids.right(x, y + 1), ids.down(x, y));
        }
    }
    return mesh;
}

Mesh meshFromTriangles(uint32_t width, uint32_t height, const std::vector<uint32_t>& triangles) {
    Mesh mesh;
    mesh.width = width;
    mesh.height = height;
    std::unordered_map<uint64_t, uint32_t> ids;  // by (smaller vertex, larger vertex)
    auto edgeOf = [&](uint32_t p, uint32_t q) {
        const auto [it, inserted] = ids.emplace(uint64_t(std::min(p, q)) << 32 | std::max(p, q), mesh.edgeCount());
        if (inserted) {
            mesh.vertices.push_back({p, q, kNone, kNone});
            mesh.neighbours.push_back({kNone, kNone, kNone, kNone});
        }
        return it->second;
    };
    for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
        const uint32_t p0 = triangles[t], p1 = triangles[t + 1], p2 = triangles[t + 2];
        const uint32_t e01 = edgeOf(p0, p1), e12 = edgeOf(p1, p2), e20 = edgeOf(p2, p0);
        attachTriangle3(mesh, p0, p1, p2, e01, e12, e20);
    }
    return mesh;
}

void flipEdge(Mesh& mesh, uint32_t e) {
    const EdgeVertices v = mesh.vertices[e];
    const EdgeNeighbours n = mesh.neighbours[e];
    assert(v.l != kNone && v.r != kNone);
    mesh.vertices[e] = {v.r, v.l, v.a, v.b};
    mesh.neighbours[e] = {n.la, n.ar, n.rb, n.bl};
    // New triangles: (r, b, l) holds bl and rb, (l, a, r) holds la and ar.
    patchNeighbour(mesh, n.bl, e, v.a, v.r, n.rb);
    patchNeighbour(mesh, n.la, e, v.b, v.r, n.ar);
    patchNeighbour(mesh, n.ar, e, v.b, v.l, n.la);
    patchNeighbour(mesh, n.rb, e, v.a, v.l, n.bl);
}

FlipStencil flipStencil(const Mesh& mesh, uint32_t e) {
    const EdgeVertices& v = mesh.vertices[e];
    const EdgeNeighbours& n = mesh.neighbours[e];
    return {v.a,
            v.b,
            v.l,
            v.r,
            farVertex(mesh, n.bl, v.a),
            farVertex(mesh, n.la, v.b),
            farVertex(mesh, n.ar, v.b),
            farVertex(mesh, n.rb, v.a)};
}

std::vector<uint32_t> regionOf(const Mesh& mesh, uint32_t e, int degree) {
    std::vector<uint32_t> region{e};
    size_t frontier_begin = 0;
    for (int step = 0; step < degree; ++step) {
        size_t frontier_end = region.size();
        for (size_t i = frontier_begin; i < frontier_end; ++i) {
            for (int k = 0; k < 4; ++k) {
                uint32_t f = neighbourAt(mesh.neighbours[region[i]], k);
                if (f != kNone && std::find(region.begin(), region.end(), f) == region.end()) region.push_back(f);
            }
        }
        frontier_begin = frontier_end;
    }
    region.erase(region.begin());
    std::sort(region.begin(), region.end());
    return region;
}

std::vector<Triangle> listTriangles(const Mesh& mesh) {
    std::vector<Triangle> triangles;
    triangles.reserve(2 * size_t(mesh.width - 1) * (mesh.height - 1));
    forEachTriangle(mesh, [&](const Triangle& t) { triangles.push_back(t); });
    return triangles;
}

namespace {

// Checks one side of edge e: the triangle (p, q, t) with its other edges e_qt, e_tp.
std::string checkSide(const Mesh& mesh, MeshHull hull, uint32_t e, uint32_t p, uint32_t q, uint32_t t, uint32_t e_qt,
                      uint32_t e_tp) {
    if (t == kNone) {
        if (e_qt != kNone || e_tp != kNone) return "missing triangle but neighbour edges set";
        if (hull == MeshHull::rectangle && !onHullSide(mesh, p, q)) return "one-sided edge not on the hull";
        return "";
    }
    if (t >= mesh.vertexCount()) return "adjacent vertex out of range";
    if (orientationSign(mesh, p, q, t) <= 0) return "triangle not positive";
    if (e_qt == kNone || e_tp == kNone || e_qt >= mesh.edgeCount() || e_tp >= mesh.edgeCount())
        return "neighbour edge missing or out of range";
    if (!joins(mesh.vertices[e_qt], q, t) || !joins(mesh.vertices[e_tp], t, p)) return "neighbour edge has wrong vertices";
    // Symmetry: each neighbour must see the same triangle, with e and the other edge as its slots.
    for (uint32_t f : {e_qt, e_tp}) {
        uint32_t other = f == e_qt ? e_tp : e_qt;
        uint32_t near = f == e_qt ? p : q;
        const EdgeVertices& fv = mesh.vertices[f];
        const EdgeNeighbours& fn = mesh.neighbours[f];
        uint32_t s0 = fv.l == near ? fn.bl : fv.r == near ? fn.ar : kNone;
        uint32_t s1 = fv.l == near ? fn.la : fv.r == near ? fn.rb : kNone;
        if (!((s0 == e && s1 == other) || (s0 == other && s1 == e))) return "neighbour links not symmetric";
    }
    return "";
}

// The one-sided edges must form one closed loop around the mesh, turning only left (or going
// straight) at each vertex, and enclose exactly the triangles' area: then the positive
// triangles tile a convex polygon whose corners are mesh vertices, the hull of the vertices.
std::string checkConvexBoundary(const Mesh& mesh, __int128 twice_area) {
    // next[q] = p for each boundary edge traversed with its triangle on the left.
    std::unordered_map<uint32_t, uint32_t> next;
    for (const EdgeVertices& v : mesh.vertices) {
        if (v.l != kNone && v.r != kNone) continue;
        const uint32_t from = v.l == kNone ? v.b : v.a, to = v.l == kNone ? v.a : v.b;
        if (!next.emplace(from, to).second) return "boundary passes a vertex twice";
    }
    if (next.size() < 3) return "boundary shorter than a triangle";
    const uint32_t start = next.begin()->first;
    uint32_t previous = start, current = next.at(start);
    size_t length = 1;
    __int128 loop_area = 0;  // the shoelace sum: twice the loop's signed area
    do {
        const auto found = next.find(current);
        if (found == next.end()) return "boundary is not closed";
        const Position p = positionOf(mesh, previous), q = positionOf(mesh, current), r = positionOf(mesh, found->second);
        if (positionOrient(p.x, p.y, q.x, q.y, r.x, r.y) < 0) return "boundary is not convex";
        loop_area += int64_t(p.x) * q.y - int64_t(q.x) * p.y;
        previous = current;
        current = found->second;
        ++length;
    } while (previous != start && length <= next.size() + 1);
    if (previous != start || length != next.size() + 1) return "boundary is more than one loop";
    if (loop_area != twice_area) return "triangles do not fill the boundary";
    return "";
}

}  // namespace

std::string checkMesh(const Mesh& mesh, MeshHull hull) {
    const uint32_t w = mesh.width, h = mesh.height;
    if (w < 2 || h < 2) return "mesh smaller than 2x2";
    if (mesh.neighbours.size() != mesh.vertices.size()) return "wrong number of edges";
    if (hull == MeshHull::rectangle && !mesh.positions.empty() && mesh.positions.size() != size_t(w) * h)
        return "wrong number of positions";
    std::vector<uint64_t> keys;
    keys.reserve(mesh.edgeCount());
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
        const EdgeVertices& v = mesh.vertices[e];
        const EdgeNeighbours& n = mesh.neighbours[e];
        std::string problem;
        if (v.a >= mesh.vertexCount() || v.b >= mesh.vertexCount() || v.a == v.b)
            problem = "main vertices invalid";
        else if (v.l == kNone && v.r == kNone)
            problem = "edge without triangles";
        if (problem.empty()) problem = checkSide(mesh, hull, e, v.a, v.b, v.l, n.bl, n.la);
        if (problem.empty()) problem = checkSide(mesh, hull, e, v.b, v.a, v.r, n.ar, n.rb);
        if (!problem.empty()) {
            std::ostringstream out;
            out << "edge " << e << " (" << v.a << ", " << v.b << ", " << v.l << ", " << v.r << "): " << problem;
            return out.str();
        }
        keys.push_back(uint64_t(std::min(v.a, v.b)) << 32 | std::max(v.a, v.b));
    }
    std::sort(keys.begin(), keys.end());
    if (std::adjacent_find(keys.begin(), keys.end()) != keys.end()) return "duplicate edge";

    const std::vector<Triangle> triangles = listTriangles(mesh);
    const uint64_t cells = uint64_t(w - 1) * (h - 1);
    // A triangulated disk has V − E + T = 1 (Euler), V the vertices its edges use: on the grid
    // V = w·h and T = 2·cells; simplification keeps it with fewer of each.
    std::vector<bool> used(mesh.vertexCount(), false);
    for (const EdgeVertices& v : mesh.vertices) used[v.a] = used[v.b] = true;
    const int64_t used_count = std::count(used.begin(), used.end(), true);
    if (used_count - int64_t(mesh.edgeCount()) + int64_t(triangles.size()) != 1) return "wrong number of triangles";
    // Each triangle's doubled area is below 2^61 (glsl/fixed_position.h); their sum may not be.
    __int128 twice_area = 0;
    for (const Triangle& t : triangles) {
        const Position p = positionOf(mesh, t.v0), q = positionOf(mesh, t.v1), r = positionOf(mesh, t.v2);
        twice_area += positionOrient(p.x, p.y, q.x, q.y, r.x, r.y);
    }
    if (hull == MeshHull::rectangle && twice_area != __int128(2 * cells) * kPositionOne * kPositionOne)
        return "total area differs from (w-1)(h-1)";
    return checkConvexBoundary(mesh, twice_area);
}

}  // namespace ddt
