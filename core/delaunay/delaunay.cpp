// Incremental Delaunay triangulation with Lawson flips (Lawson 1977; the ghost triangles of
// Shewchuk's lecture notes, "Lecture Notes on Delaunay Mesh Generation", 1999): the points are
// inserted in a biased randomized order along a Hilbert curve, each located by a visibility
// walk from the previous one's triangle, its triangle (or edge) split, and the edges opposite
// it flipped until locally Delaunay. Only the exact predicates of predicates.h decide, so the
// result is the unique perturbed Delaunay triangulation whatever the order.
//
// Storage: triangles as flat arrays, three corners and three twins each. The hull is closed by
// ghost triangles, whose third corner is the infinite vertex, so that a point outside the hull
// is inserted like any other: the plane becomes a sphere without boundary.
//
// Measured (Release, one core of a shared 2-core VM, best of 5, CPU time): 10^5 uniform random
// points in 0.13 s, 10^6 in 1.45 s — ordering 0.13 s, insertion 0.43 s (3.1 walk steps and
// 3.0 flips a point), the canonical Mesh 0.76 s, about half of that the first touch of its
// 96 MB and of the scratch arrays (page faults cost 3 ms/MB on that VM).
#include "delaunay.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <sstream>

#include "predicates.h"

namespace ddt {

namespace {

// Coordinates lie in [0, 2^26) (predicates.h).
constexpr int32_t kCoordinateLimit = int32_t(kMaxDelaunaySide) * kPositionOne;
static_assert(kCoordinateLimit == 1 << 26);

// The infinite vertex, third corner of every ghost triangle.
constexpr uint32_t kInfinite = kNone;

// A side is 3 · t + i: triangle t's edge opposite its corner i, running from corner i + 1 to
// corner i + 2 (counter-clockwise in the positive orientation). Its twin is the same edge seen
// from the triangle across.
inline uint32_t nextSide(uint32_t s) { return s % 3 == 2 ? s - 2 : s + 1; }
inline uint32_t previousSide(uint32_t s) { return s % 3 == 0 ? s + 2 : s - 1; }

// Index of (x, y) along the Hilbert curve of a 2^16 × 2^16 grid (the classic bit-by-bit walk
// down the curve's quadrant tree, rotating the frame as the curve does).
uint32_t hilbertIndex(uint32_t x, uint32_t y) {
    const uint32_t mask = 0xFFFF;
    uint32_t index = 0;
    for (uint32_t s = 1u << 15; s > 0; s >>= 1) {
        const uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
        index += s * s * ((3 * rx) ^ ry);
        if (ry == 0) {
            if (rx == 1) {
                x = mask ^ x;
                y = mask ^ y;
            }
            std::swap(x, y);
        }
    }
    return index;
}

// Sorts entries (Hilbert index << 32 | id) by index, stably: LSD radix sort on 11-bit digits.
void sortByHilbertIndex(uint64_t* begin, uint64_t* end, uint64_t* scratch) {
    uint64_t *from = begin, *to = scratch;
    for (int digit_shift = 32; digit_shift < 64; digit_shift += 11) {
        uint32_t start[2049] = {};
        for (const uint64_t* k = from; k != from + (end - begin); ++k) ++start[((*k >> digit_shift) & 2047) + 1];
        for (int d = 1; d < 2049; ++d) start[d] += start[d - 1];
        for (const uint64_t* k = from; k != from + (end - begin); ++k) to[start[(*k >> digit_shift) & 2047]++] = *k;
        std::swap(from, to);
    }
    if (from != begin) std::copy(from, from + (end - begin), begin);
}

// A mixing hash of a point's id (splitmix64's finaliser): its round in the insertion order.
uint64_t mixedBits(uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

// The insertion order: a biased randomized insertion order (BRIO; Amenta, Choi and Rote,
// "Incremental constructions con BRIO", 2003). Each point joins a round at random, the last
// round half of the points, the one before it a quarter, and so on down to a first round of
// 32 to 64; within a round the points go along the Hilbert curve over the bounding box, so
// consecutive points are near and each walk is short. The randomness bounds the flips: with
// the Hilbert order alone, points on two lines took 680 flips a point at 20 000 points (and
// growing), against 4.6 for uniform points; a random round keeps every insertion's expected
// degree, hence its flips, constant whatever the points.
std::vector<uint32_t> insertionOrder(const std::vector<Position>& points) {
    const uint32_t n = uint32_t(points.size());
    int32_t min_x = kCoordinateLimit, min_y = kCoordinateLimit, max_x = 0, max_y = 0;
    for (const Position& p : points) {
        min_x = std::min(min_x, p.x);
        min_y = std::min(min_y, p.y);
        max_x = std::max(max_x, p.x);
        max_y = std::max(max_y, p.y);
    }
    const uint32_t span = uint32_t(std::max(max_x - min_x, max_y - min_y));
    uint32_t shift = 0;
    while ((span >> shift) > 0xFFFF) ++shift;

    // A point's level is its hash's count of leading zeros, capped at `top`: level k holds
    // about n / 2^(k + 1) points, the capped one fewer than 64. Round r = top − level.
    const int top = std::bit_width(n / 64);
    auto level = [&](uint32_t i) { return std::min(std::countl_zero(mixedBits(i) | 1), top); };
    std::vector<uint32_t> round_start(top + 2, 0);
    for (uint32_t i = 0; i < n; ++i) ++round_start[top - level(i) + 1];
    for (int r = 1; r <= top + 1; ++r) round_start[r] += round_start[r - 1];
    std::vector<uint64_t> keyed(n), scratch(n);
    {
        std::vector<uint32_t> fill(round_start.begin(), round_start.end() - 1);
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t index =
                hilbertIndex(uint32_t(points[i].x - min_x) >> shift, uint32_t(points[i].y - min_y) >> shift);
            keyed[fill[top - level(i)]++] = uint64_t(index) << 32 | i;
        }
    }
    for (int r = 0; r <= top; ++r)
        sortByHilbertIndex(keyed.data() + round_start[r], keyed.data() + round_start[r + 1], scratch.data());
    std::vector<uint32_t> order(n);
    for (uint32_t i = 0; i < n; ++i) order[i] = uint32_t(keyed[i]);
    return order;
}

// Sorts a vertex's star: insertion sort for the usual six or so sides, std::sort for the rare
// vertex of high degree (the apex of a fan over collinear points).
void sortStar(std::vector<uint64_t>& star) {
    if (star.size() > 16) {
        std::sort(star.begin(), star.end());
        return;
    }
    for (size_t i = 1; i < star.size(); ++i) {
        const uint64_t key = star[i];
        size_t k = i;
        for (; k > 0 && star[k - 1] > key; --k) star[k] = star[k - 1];
        star[k] = key;
    }
}

class Triangulator {
public:
    explicit Triangulator(const std::vector<Position>& points) : points_(points) {}

    void run();
    // The canonical Mesh of the finished triangulation, vertex ids as the points' indices.
    Mesh mesh(uint32_t width, uint32_t height) const;

private:
    // Where a point lies: inside `triangle` (a real one, or a ghost whose hull edge the point
    // sees), or on side `side` of a real triangle (kNone if not on a side).
    struct Location {
        uint32_t triangle;
        uint32_t side;
    };

    const Position& at(uint32_t v) const { return points_[v]; }
    bool isGhost(uint32_t t) const {
        return corner_[3 * t] == kInfinite || corner_[3 * t + 1] == kInfinite || corner_[3 * t + 2] == kInfinite;
    }
    uint32_t newTriangle(uint32_t a, uint32_t b, uint32_t c) {
        const uint32_t t = triangle_count_++;
        corner_[3 * t] = a;
        corner_[3 * t + 1] = b;
        corner_[3 * t + 2] = c;
        return t;
    }
    void setCorners(uint32_t t, uint32_t a, uint32_t b, uint32_t c) {
        corner_[3 * t] = a;
        corner_[3 * t + 1] = b;
        corner_[3 * t + 2] = c;
    }
    void link(uint32_t s, uint32_t u) {
        twin_[s] = u;
        twin_[u] = s;
    }
    // xorshift32: the walk's random choice of which side to test first.
    uint32_t random() {
        rng_ ^= rng_ << 13;
        rng_ ^= rng_ >> 17;
        rng_ ^= rng_ << 5;
        return rng_;
    }

    void start(uint32_t a, uint32_t b, uint32_t c);
    Location locate(Position p);
    void splitTriangle(uint32_t t, uint32_t p);
    void splitSide(uint32_t s, uint32_t p);
    bool mustFlip(uint32_t s) const;
    void flip(uint32_t s);
    void legalize();

    const std::vector<Position>& points_;
    std::vector<uint32_t> corner_;  // 3 per triangle: vertex ids, or kInfinite
    std::vector<uint32_t> twin_;    // 3 per side: the twin side
    uint32_t triangle_count_ = 0;
    std::vector<uint32_t> pending_;  // sides opposite the new point still to legalize
    uint32_t last_ = 0;              // a triangle around the last point inserted
    uint32_t rng_ = 2463534242u;
};

void Triangulator::run() {
    const uint32_t n = uint32_t(points_.size());
    assert(n >= 3);
    // A sphere triangulated on n + 1 vertices (the infinite one included) has 2(n + 1) − 4
    // triangles.
    corner_.resize(3 * (2 * size_t(n) - 2));
    twin_.resize(corner_.size());
    const std::vector<uint32_t> order = insertionOrder(points_);

    // The first triangle: the first two points and the first point off their line. Points on
    // the line before it are inserted after it like the others (on its side, or outside).
    size_t third = 2;
    while (third < n && orient(at(order[0]), at(order[1]), at(order[third])) == 0) ++third;
    assert(third < n);  // not all collinear
    if (orient(at(order[0]), at(order[1]), at(order[third])) > 0)
        start(order[0], order[1], order[third]);
    else
        start(order[1], order[0], order[third]);

    for (size_t k = 2; k < n; ++k) {
        if (k == third) continue;
        const uint32_t p = order[k];
        const Location location = locate(at(p));
        if (location.side == kNone)
            splitTriangle(location.triangle, p);
        else
            splitSide(location.side, p);
        legalize();
    }
    assert(triangle_count_ == 2 * n - 2);
}

// The positive triangle (a, b, c) and the three ghosts across its sides.
void Triangulator::start(uint32_t a, uint32_t b, uint32_t c) {
    const uint32_t t = newTriangle(a, b, c);
    const uint32_t g_a = newTriangle(c, b, kInfinite);  // across side b → c
    const uint32_t g_b = newTriangle(a, c, kInfinite);  // across c → a
    const uint32_t g_c = newTriangle(b, a, kInfinite);  // across a → b
    link(3 * t + 0, 3 * g_a + 2);
    link(3 * t + 1, 3 * g_b + 2);
    link(3 * t + 2, 3 * g_c + 2);
    // Ghost to ghost, along the edges to the infinite vertex: b–∞, c–∞, a–∞.
    link(3 * g_a + 0, 3 * g_c + 1);
    link(3 * g_b + 0, 3 * g_a + 1);
    link(3 * g_c + 0, 3 * g_b + 1);
    last_ = t;
}

// A visibility walk from the last point's triangle: cross any side that has p strictly on its
// far side, until none has (p is in the closed triangle) or a ghost is reached (p is strictly
// outside the hull edge just crossed). It ends on a Delaunay triangulation, whose "in front
// of" relation seen from any point is acyclic (Edelsbrunner 1990, also for the perturbed
// lifts, a regular triangulation); the random first side guards the degenerate cases all the
// same.
Triangulator::Location Triangulator::locate(Position p) {
    uint32_t t = last_;
    if (isGhost(t)) {
        // Step across its hull edge, the side opposite the infinite corner.
        const uint32_t i = corner_[3 * t] == kInfinite ? 0 : corner_[3 * t + 1] == kInfinite ? 1 : 2;
        t = twin_[3 * t + i] / 3;
    }
    uint32_t entered = kNone;  // the side of t the walk came through (p strictly inside it)
    for (;;) {
        const uint32_t first = random() % 3;
        int64_t side_orient[3] = {1, 1, 1};
        uint32_t exit = kNone;
        for (uint32_t k = 0; k < 3; ++k) {
            const uint32_t i = (first + k) % 3;
            const uint32_t s = 3 * t + i;
            if (s == entered) continue;
            side_orient[i] = orient(at(corner_[3 * t + (i + 1) % 3]), at(corner_[3 * t + (i + 2) % 3]), p);
            if (side_orient[i] < 0) {
                exit = s;
                break;
            }
        }
        if (exit == kNone) {
            // Two zero sides would put p on a corner: distinct points never do.
            for (uint32_t i = 0; i < 3; ++i)
                if (side_orient[i] == 0) return {t, 3 * t + i};
            return {t, kNone};
        }
        entered = twin_[exit];
        t = entered / 3;
        if (isGhost(t)) return {t, kNone};
    }
}

// p strictly inside t = (a, b, c), or, for a ghost, strictly outside its hull edge: three
// triangles (p, b, c), (a, p, c), (a, b, p), the first in t's place.
void Triangulator::splitTriangle(uint32_t t, uint32_t p) {
    const uint32_t a = corner_[3 * t], b = corner_[3 * t + 1], c = corner_[3 * t + 2];
    const uint32_t n_b = twin_[3 * t + 1], n_c = twin_[3 * t + 2];
    setCorners(t, p, b, c);
    const uint32_t t1 = newTriangle(a, p, c);
    const uint32_t t2 = newTriangle(a, b, p);
    link(3 * t + 1, 3 * t1 + 0);
    link(3 * t + 2, 3 * t2 + 0);
    link(3 * t1 + 2, 3 * t2 + 1);
    link(3 * t1 + 1, n_b);
    link(3 * t2 + 2, n_c);
    pending_.push_back(3 * t + 0);
    pending_.push_back(3 * t1 + 1);
    pending_.push_back(3 * t2 + 2);
    last_ = t;
}

// p inside side s = b → c of t = (a, b, c), whose twin belongs to t' = (w, c, b) (w may be
// the infinite vertex: p on a hull edge). Four triangles: (p, a, b) and (p, c, a) in t,
// (p, w, c) and (p, b, w) in t'.
void Triangulator::splitSide(uint32_t s, uint32_t p) {
    const uint32_t t = s / 3, h = twin_[s], u = h / 3;
    const uint32_t a = corner_[s], b = corner_[nextSide(s)], c = corner_[previousSide(s)], w = corner_[h];
    const uint32_t n_b = twin_[nextSide(s)], n_c = twin_[previousSide(s)];      // c → a, a → b
    const uint32_t m_c = twin_[nextSide(h)], m_b = twin_[previousSide(h)];      // b → w, w → c
    setCorners(t, p, a, b);
    const uint32_t t1 = newTriangle(p, c, a);
    setCorners(u, p, w, c);
    const uint32_t t3 = newTriangle(p, b, w);
    link(3 * t + 0, n_c);
    link(3 * t + 1, 3 * t3 + 2);
    link(3 * t + 2, 3 * t1 + 1);
    link(3 * t1 + 0, n_b);
    link(3 * t1 + 2, 3 * u + 1);
    link(3 * u + 0, m_b);
    link(3 * u + 2, 3 * t3 + 1);
    link(3 * t3 + 0, m_c);
    for (uint32_t triangle : {t, t1, u, t3}) pending_.push_back(3 * triangle);
    last_ = t;
}

// Whether side s = u → v of (p, u, v), p the new point, must flip: the far corner w of its
// twin's triangle (v, u, w) lies inside the circumcircle of (p, u, v). A ghost's circumcircle
// is the open half-plane beyond its hull edge (plus the open edge, where p never is): a ghost
// edge u–∞ flips iff p strictly sees the next hull edge, which makes the hull convex again;
// a hull edge never flips towards a point inside it.
bool Triangulator::mustFlip(uint32_t s) const {
    const uint32_t p = corner_[s], u = corner_[nextSide(s)], v = corner_[previousSide(s)];
    const uint32_t w = corner_[twin_[s]];
    if (w == kInfinite) return false;
    if (u == kInfinite) return orient(at(w), at(v), at(p)) > 0;  // twin (w, v, ∞): hull edge w → v
    if (v == kInfinite) return orient(at(u), at(w), at(p)) > 0;  // twin (u, w, ∞): hull edge u → w
    return inCircle(at(p), at(u), at(v), at(w));
}

// Flips side s = u → v of t = (p, u, v) with its twin in t' = (w, v, u): t becomes (p, u, w)
// and t' (p, w, v), p keeping its slot in t and taking the twin's slot in t'.
void Triangulator::flip(uint32_t s) {
    const uint32_t h = twin_[s];
    const uint32_t s1 = nextSide(s), s2 = nextSide(s1);  // t's sides opposite u and v
    const uint32_t h1 = nextSide(h), h2 = nextSide(h1);  // t''s sides opposite v and u
    const uint32_t p = corner_[s], w = corner_[h], v = corner_[h1];
    const uint32_t across_vp = twin_[s1], across_uw = twin_[h1], across_wv = twin_[h2];
    corner_[s2] = w;
    corner_[h] = p;
    corner_[h1] = w;
    corner_[h2] = v;
    link(s, across_uw);
    link(s1, h2);
    link(h, across_wv);
    link(h1, across_vp);
    pending_.push_back(s);
    pending_.push_back(h);
}

void Triangulator::legalize() {
    while (!pending_.empty()) {
        const uint32_t s = pending_.back();
        pending_.pop_back();
        if (mustFlip(s)) flip(s);
    }
}

// The canonical numbering needs each vertex's edges to larger vertices in order. They are
// gathered by walking around each vertex, in the triangles' order rather than the ids': the
// ids of uniform points in row-major order are far apart in the plane, the triangles of a
// vertex's star near each other in memory (they were made around the same insertions). The
// records are then written in id order: sequential writes to the largest arrays beat reads in
// order (measured, 0.09 s against 0.2 s at 10^6 points).
Mesh Triangulator::mesh(uint32_t width, uint32_t height) const {
    const uint32_t n = uint32_t(points_.size());
    auto from = [&](uint32_t s) { return corner_[nextSide(s)]; };
    auto to = [&](uint32_t s) { return corner_[previousSide(s)]; };

    // Each vertex's edges to larger vertices: the prefix sums give the first edge id of each.
    // Every edge is counted once: from its real side a → b (a < b), or its only real side.
    std::vector<uint32_t> first_edge(n + 1, 0);
    for (uint32_t t = 0; t < triangle_count_; ++t) {
        if (isGhost(t)) continue;
        for (uint32_t s = 3 * t; s < 3 * t + 3; ++s)
            if (from(s) < to(s) || corner_[twin_[s]] == kInfinite) ++first_edge[std::min(from(s), to(s)) + 1];
    }
    for (uint32_t v = 0; v < n; ++v) first_edge[v + 1] += first_edge[v];
    const uint32_t edge_count = first_edge[n];

    // Walk around each vertex u through its outgoing sides u → x (s → nextSide(twin s)), sort
    // those with x > u by x, and number them; each side and its twin learn their edge.
    std::vector<bool> visited(n, false);
    std::vector<uint32_t> edge_side(edge_count), side_edge(3 * size_t(triangle_count_));
    std::vector<uint64_t> star;  // x << 32 | side
    for (uint32_t c = 0; c < 3 * triangle_count_; ++c) {
        const uint32_t u = corner_[c];
        if (u == kInfinite || visited[u]) continue;
        visited[u] = true;
        star.clear();
        const uint32_t first = previousSide(c);  // u → the next corner
        uint32_t s = first;
        do {
            if (const uint32_t x = to(s); x != kInfinite && x > u) star.push_back(uint64_t(x) << 32 | s);
            s = nextSide(twin_[s]);
        } while (s != first);
        sortStar(star);
        assert(star.size() == first_edge[u + 1] - first_edge[u]);
        for (uint32_t k = 0; k < star.size(); ++k) {
            const uint32_t e = first_edge[u] + k, side = uint32_t(star[k]);
            edge_side[e] = side;
            side_edge[side] = side_edge[twin_[side]] = e;
        }
    }

    // The records, each from its two sides: side u → v of (x, u, v) is the left triangle
    // (a, b, l) of its edge if u < v, else the right one (b, a, r); either way the neighbours
    // on that side are the edges opposite u and v, in the glossary's order (bl, la or ar, rb).
    Mesh mesh;
    mesh.width = width;
    mesh.height = height;
    mesh.hull = MeshHull::convex;
    mesh.vertices.resize(edge_count);
    mesh.neighbours.resize(edge_count);
    for (uint32_t u = 0; u < n; ++u) {
        for (uint32_t e = first_edge[u]; e < first_edge[u + 1]; ++e) {
            EdgeVertices& ev = mesh.vertices[e];
            EdgeNeighbours& en = mesh.neighbours[e];
            ev = {u, to(edge_side[e]), kNone, kNone};
            en = {kNone, kNone, kNone, kNone};
            for (const uint32_t side : {edge_side[e], twin_[edge_side[e]]}) {
                const uint32_t x = corner_[side];
                if (x == kInfinite) continue;
                const uint32_t opposite_from = side_edge[nextSide(side)], opposite_to = side_edge[previousSide(side)];
                if (from(side) == u) {
                    ev.l = x;
                    en.bl = opposite_from;
                    en.la = opposite_to;
                } else {
                    ev.r = x;
                    en.ar = opposite_from;
                    en.rb = opposite_to;
                }
            }
        }
    }
    return mesh;
}

void assertInFrame(uint32_t width, uint32_t height, const std::vector<Position>& points) {
    (void)width, (void)height, (void)points;
    assert(width <= kMaxDelaunaySide && height <= kMaxDelaunaySide);
#ifndef NDEBUG
    for (const Position& p : points)
        assert(p.x >= 0 && p.y >= 0 && p.x <= int32_t(width - 1) * kPositionOne &&
               p.y <= int32_t(height - 1) * kPositionOne);
#endif
}

}  // namespace

std::string delaunayInputProblem(const std::vector<Position>& points) {
    if (points.size() < 3) return "fewer than 3 points";
    for (const Position& p : points)
        if (p.x < 0 || p.y < 0 || p.x >= kCoordinateLimit || p.y >= kCoordinateLimit)
            return "a point outside the range [0, 2^26)";
    std::vector<Position> sorted = points;
    std::sort(sorted.begin(), sorted.end(), [](Position p, Position q) { return p.y != q.y ? p.y < q.y : p.x < q.x; });
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return "two points at the same place";
    for (const Position& p : points)
        if (orient(points[0], points[1], p) != 0) return "";
    return "all points are collinear";
}

Mesh delaunayOfPixels(uint32_t width, uint32_t height, const std::vector<uint32_t>& pixel_ids) {
    std::vector<Position> points(pixel_ids.size());
    for (size_t i = 0; i < pixel_ids.size(); ++i) {
        assert(pixel_ids[i] < uint64_t(width) * height && (i == 0 || pixel_ids[i - 1] < pixel_ids[i]));
        points[i] = gridPosition(pixel_ids[i], width);
    }
    assertInFrame(width, height, points);
    assert(delaunayInputProblem(points).empty());
    Triangulator triangulator(points);
    triangulator.run();
    Mesh mesh = triangulator.mesh(width, height);
    // Local ids ascend with the pixel ids, so the canonical order carries over.
    for (EdgeVertices& v : mesh.vertices) {
        v.a = pixel_ids[v.a];
        v.b = pixel_ids[v.b];
        if (v.l != kNone) v.l = pixel_ids[v.l];
        if (v.r != kNone) v.r = pixel_ids[v.r];
    }
    return mesh;
}

Mesh delaunayOfPoints(uint32_t width, uint32_t height, const std::vector<Position>& points) {
    assertInFrame(width, height, points);
    assert(delaunayInputProblem(points).empty());
    Triangulator triangulator(points);
    triangulator.run();
    Mesh mesh = triangulator.mesh(width, height);
    mesh.positions = points;
    return mesh;
}

std::string checkDelaunay(const Mesh& mesh) {
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
        const EdgeVertices& v = mesh.vertices[e];
        if (v.l == kNone || v.r == kNone) continue;
        const Position a = positionOf(mesh, v.a), b = positionOf(mesh, v.b);
        const Position l = positionOf(mesh, v.l), r = positionOf(mesh, v.r);
        std::string problem;
        for (const Position& p : {a, b, l, r})
            if (p.x < 0 || p.y < 0 || p.x >= kCoordinateLimit || p.y >= kCoordinateLimit)
                problem = "vertex outside the range [0, 2^26)";
        if (problem.empty() && orient(a, b, l) <= 0) problem = "left triangle not positive";
        if (problem.empty() && inCircle(a, b, l, r)) problem = "not locally Delaunay";
        if (!problem.empty()) {
            std::ostringstream out;
            out << "edge " << e << " (" << v.a << ", " << v.b << ", " << v.l << ", " << v.r << "): " << problem;
            return out.str();
        }
    }
    return "";
}

}  // namespace ddt
