// Sederberg's cost function (SCF), its face-weighted form (face-SCF) and the gain of an edge
// flip, written once in the common subset of C++ and GLSL: core/image/cost.cpp and the kernels
// include this file, so the serial reference and the Vulkan backend evaluate numerically the
// same formula. The variance weight and the choice among the costs: glsl/image/content_cost.h.
// Paper: Červeňanský et al., "Parallel GPU-based data-dependent triangulations", Sec. 2.1;
// face-SCF: Tóth et al., "N-dimensional data-dependent reconstruction using topological
// changes", Sect. 3.
//
// A vertex is named by its id; its coordinates (its place, see Places below) are its pixel
// centre (x, y) = (id % width, id / width) on the grid, or its explicit position.
// A triangle is passed in positive orientation (see core/image/mesh.h for the convention).
#ifndef DDTUP_SEDERBERG_H
#define DDTUP_SEDERBERG_H

#include "fixed_position.h"

#ifdef __cplusplus
#include <cmath>
#include <cstdint>
namespace ddt {
typedef uint32_t uint;
#define DDT_FN inline
#define DDT_PRECISE
using std::sqrt;
#else
#define DDT_FN
// `precise` forbids fused multiply-add contraction, so a kernel rounds exactly like the
// C++ code compiled for x86-64 (no FMA without -mfma).
#define DDT_PRECISE precise
#endif

// A missing vertex or edge (the outer side of a boundary edge).
const uint kNone = 0xFFFFFFFFu;

// An edge is flipped only when its gain exceeds this. With a bare "gain > 0" rule, rounding
// noise of ~1e-16 makes an edge flip back and forth forever; a flip's gain is a sum of five
// edge costs of at most ~8 each, so its rounding error stays below ~1e-14. The content-weighted
// costs read the same luma in [0, 1] and their terms are smaller still (every triangle of the
// grid's triangulations has area 1/2, see glsl/image/content_cost.h): face-SCF's a third of SCF's,
// variance's at most 1/2 · 2/9. Their rounding noise stays below ~1e-14 as well, so the
// threshold keeps its meaning for them unscaled.
//
// On meshes with explicit positions the triangles have any size, and the threshold, absolute,
// keeps that meaning only for triangles of about the grid's size. With the values fixed,
// scaling every position by s scales each plane gradient by 1/s, so an edge's SCF by 1/s²,
// face-SCF's share (SCF × area) by 1 (scale-free), variance's share (area × variance) by s².
// - Small or thin triangles: a triangle of height h pixels has a gradient of up to ~1/h, an
//   SCF of up to ~2/h², and a gain whose rounding noise (~1e-15 of its terms) passes 1e-12
//   once h < ~0.05 px for SCF; face-SCF's share grows as the aspect ratio (length / h), not
//   the size. Points closer than ~1/20 px, or slivers, can flip on noise (then only the
//   optimizers' caps end the sweeps).
// - Large triangles: SCF of triangles L pixels across is below ~8/L²; at L ≈ 300 the ignored
//   gains below 1e-12 are ~1e-8 of an edge's largest SCF: negligible. Variance's share (at
//   most 2/9 of the area) grows as the area; its noise reaches 1e-12 beyond ~1e4 px².
// Points at least a few tenths of a pixel apart (the jittered grids of the tests, samples of
// an image) stay well inside both bounds. A threshold relative to the gain's terms would lift
// both bounds, at the price of changing every cost's flips on the grid.
#ifdef __cplusplus
const double kFlipGainThreshold = 1e-12;
#else
const double kFlipGainThreshold = 1e-12lf;  // lf: a plain 1e-12 would be a float literal
#endif

// Where the formulas find the vertices (their places): on the grid (a mesh without explicit
// positions, core/image/mesh.h) vertex id = y · width + x lies at its pixel centre (x, y), computed
// from the id (the fast path); a mesh with explicit positions gives each vertex id its
// fixed-point position (glsl/fixed_position.h). C++ passes the positions' array; a kernel
// reads them from its positions buffer (glsl/image/common.glsl), chosen by a specialization
// constant, so the grid's kernels compile without the reads.
#ifdef __cplusplus
struct Places {
    uint width;                 // the grid's: ids of pixel centres count in rows of `width`
    const Position* positions;  // per vertex id, or nullptr: every vertex at its pixel centre
};
DDT_FN bool hasPositions(Places places) { return places.positions != nullptr; }
DDT_FN Position positionAt(Places places, uint v) { return places.positions[v]; }
#else
struct Places {
    uint width;
    bool positioned;  // kPositioned in the kernels
};
bool hasPositions(Places places) { return places.positioned; }
// Vertex v's explicit position: defined by the kernels that include this file (glsl/image/common.glsl).
Position vertexPosition(uint v);
Position positionAt(Places places, uint v) { return vertexPosition(v); }
#endif

// The row of grid vertex `id`, id / width (its column is id − row · width).
#ifdef __cplusplus
DDT_FN uint gridRow(uint id, uint width) { return id / width; }
#else
// lavapipe divides integers lane by lane (x86 has no vector integer division), and the grid's
// cost formulas would divide six times per triangle; a double multiplication by the reciprocal
// (one division per kernel: width is uniform) is one cheap vector instruction. id · fl(1/width)
// is within a few ulps of id / width < 2^32, so its truncation is off by at most one, which
// the remainder's range corrects: exact for every uint id and every width below 2^31.
uint gridRow(uint id, uint width) {
    uint row = uint(double(id) * (1.0lf / double(width)));
    const uint rest = id - row * width;  // modulo 2^32: "negative" when row is one too large
    if (int(rest) < 0) row -= 1;
    else if (rest >= width) row += 1;
    return row;
}
#endif

// The triangle (i0, i1, i2) as the formulas read it: its sides from i0 and twice its signed area.
struct TriangleSides {
    double dx1, dy1;    // place of i1 − place of i0, in pixels
    double dx2, dy2;    // place of i2 − place of i0
    double twice_area;  // orient(i0, i1, i2), positive for positive orientation
};

// Every coordinate difference is exact in double: on the grid a difference of integers; with
// positions an int32 difference of fixed-point coordinates in [0, 2^30) (below 2^30 in
// magnitude), times the power of two 1 / kPositionOne. Twice the area: on the grid the products
// are integers below w · h < 2^32, exact; with positions they would need up to 61 bits and
// round, and a thin triangle could get the wrong sign, so it is positionOrient's exact int64
// value (glsl/fixed_position.h) converted once, correctly rounded, its sign kept, then scaled
// by the power of two 1 / kPositionOne², exactly. Positions at the pixel centres give the
// grid's values bit for bit.
DDT_FN TriangleSides triangleSides(uint i0, uint i1, uint i2, Places places) {
    DDT_PRECISE double dx1, dy1, dx2, dy2;
    // Not `precise`: a kernel may fuse the grid's products, which are exact (and positions
    // have none), into a multiply-add without changing a bit, as it did before positions.
    double twice_area;
    if (hasPositions(places)) {
        const Position p0 = positionAt(places, i0), p1 = positionAt(places, i1), p2 = positionAt(places, i2);
        const double unit = 1.0 / double(kPositionOne);
        dx1 = double(p1.x - p0.x) * unit;
        dy1 = double(p1.y - p0.y) * unit;
        dx2 = double(p2.x - p0.x) * unit;
        dy2 = double(p2.y - p0.y) * unit;
        twice_area = double(positionOrient(p0.x, p0.y, p1.x, p1.y, p2.x, p2.y)) * (unit * unit);
    } else {
        const uint width = places.width;
        const uint y0 = gridRow(i0, width), y1 = gridRow(i1, width), y2 = gridRow(i2, width);
        dx1 = double(i1 - y1 * width) - double(i0 - y0 * width);
        dy1 = double(y1) - double(y0);
        dx2 = double(i2 - y2 * width) - double(i0 - y0 * width);
        dy2 = double(y2) - double(y0);
        twice_area = dx1 * dy2 - dx2 * dy1;
    }
    TriangleSides t;
    t.dx1 = dx1;
    t.dy1 = dy1;
    t.dx2 = dx2;
    t.dy2 = dy2;
    t.twice_area = twice_area;
    return t;
}

// The gradient of a triangle's plane as n / d: n is the cross-product numerator, d twice the
// signed area. Keeping the division out of the gradient lets the SCF divide once.
struct Gradient {
    double x;      // n.x
    double y;      // n.y
    double scale;  // d
};

// Gradient of the plane z = a x + b y + c through three vertices with values z0..z2.
// The triangle is first rotated so its smallest vertex id comes first (orientation kept):
// every edge that asks for this triangle then gets a bit-identical gradient.
DDT_FN Gradient planeGradient(uint i0, uint i1, uint i2, float z0, float z1, float z2, Places places) {
    if (i1 < i0 && i1 < i2) {
        uint t = i0; i0 = i1; i1 = i2; i2 = t;
        float s = z0; z0 = z1; z1 = z2; z2 = s;
    } else if (i2 < i0 && i2 < i1) {
        uint t = i0; i0 = i2; i2 = i1; i1 = t;
        float s = z0; z0 = z2; z2 = z1; z1 = s;
    }
    const TriangleSides t = triangleSides(i0, i1, i2, places);
    DDT_PRECISE double dz1 = double(z1) - double(z0);
    DDT_PRECISE double dz2 = double(z2) - double(z0);
    Gradient g;
    g.x = dz1 * t.dy2 - dz2 * t.dy1;
    g.y = dz2 * t.dx1 - dz1 * t.dx2;
    g.scale = t.twice_area;
    return g;
}

// SCF of an edge between two triangles: |∇P1|·|∇P2| − ∇P1·∇P2 (zero when the planes are
// parallel, largest when they fold against each other). With ∇P = n / d this is
// (sqrt(|n1|²·|n2|²) − n1·n2) / (d1·d2): one square root and at most one division per edge.
// Symmetric in its two arguments.
DDT_FN double sederbergCost(Gradient g1, Gradient g2) {
    DDT_PRECISE double norms = sqrt((g1.x * g1.x + g1.y * g1.y) * (g2.x * g2.x + g2.y * g2.y));
    DDT_PRECISE double dot = g1.x * g2.x + g1.y * g2.y;
    DDT_PRECISE double areas = g1.scale * g2.scale;
    // A triangle of a mesh on every pixel centre holds no centre but its corners, so by Pick's
    // theorem twice its area is 1; x / 1 is x exactly, so skipping the division (a slow
    // instruction, the gain's bottleneck with the square roots) changes no bit.
    if (areas == 1.0) return norms - dot;
    return (norms - dot) / areas;
}

// Face-SCF's share of an edge (Tóth et al., "N-dimensional data-dependent reconstruction
// using topological changes", Sect. 3): a triangle T weighs area(T) · w(T), w(T) the mean
// of the SCF over its three edges (a boundary edge 0), so an edge's SCF counts a third for
// each of its two triangles:  scf · (area1 + area2) / 3 = scf · (d1 + d2) / 6.
// On the grid d1 + d2 is an exact integer sum; with positions it may round, but a floating-
// point sum does not depend on the order of its two terms: the share is symmetric bit for bit.
DDT_FN double faceScfCost(Gradient g1, Gradient g2) {
    DDT_PRECISE double twice_areas = g1.scale + g2.scale;
    DDT_PRECISE double share = sederbergCost(g1, g2) * twice_areas;
    return share / 6.0;
}

// The cost an edge between two triangles adds to the mesh: its SCF (Sederberg's cost), or
// with `face_weighted` its face-SCF share.
DDT_FN double pairCost(Gradient g1, Gradient g2, bool face_weighted) {
    return face_weighted ? faceScfCost(g1, g2) : sederbergCost(g1, g2);
}

// Twice the signed area of (i0, i1, i2) in square pixels; positive for positive orientation.
// Its sign is exact (triangleSides).
DDT_FN double orientation(uint i0, uint i1, uint i2, Places places) {
    return triangleSides(i0, i1, i2, places).twice_area;
}

// The vertices a flip of edge e reads: its quadrilateral a, b, l, r and the far vertices of
// its four neighbour edges b–l, l–a, a–r, r–b (kNone where a neighbour is a boundary edge).
struct FlipStencil {
    uint a, b, l, r;
    uint far_bl, far_la, far_ar, far_rb;
};

// Values of one channel at the stencil's vertices (0 where the vertex is kNone).
struct StencilValues {
    float a, b, l, r;
    float far_bl, far_la, far_ar, far_rb;
};

// A flip is allowed only across a strictly convex quadrilateral a, r, b, l: both new
// triangles (r, b, l) and (l, a, r) must have positive area. Exact: orientation's sign is.
DDT_FN bool flipIsConvex(FlipStencil s, Places places) {
    return s.l != kNone && s.r != kNone &&
           orientation(s.r, s.b, s.l, places) > 0.0 && orientation(s.l, s.a, s.r, places) > 0.0;
}

// pairCost of a neighbour edge between an inner triangle (gradient g) and its outer triangle
// (i0, i1, far); a boundary neighbour (far == kNone) costs 0.
DDT_FN double neighbourCost(Gradient g, uint i0, uint i1, uint far, float z0, float z1, float zfar, Places places,
                            bool face_weighted) {
    if (far == kNone) return 0.0;
    return pairCost(g, planeGradient(i0, i1, far, z0, z1, zfar, places), face_weighted);
}

// Whether every value the gain reads is the same: then every plane is flat and the gain is
// exactly 0, which the full formula would also return, at far greater cost (flat regions
// are common in drawings).
DDT_FN bool stencilIsFlat(FlipStencil s, StencilValues z) {
    return z.b == z.a && z.l == z.a && z.r == z.a && (s.far_bl == kNone || z.far_bl == z.a) &&
           (s.far_la == kNone || z.far_la == z.a) && (s.far_ar == kNone || z.far_ar == z.a) &&
           (s.far_rb == kNone || z.far_rb == z.a);
}

// Cost decrease over the five edges a flip changes (the edge and its four neighbours) for
// one channel: of Sederberg's cost, or with `face_weighted` of face-SCF. Face-SCF changes on
// the same five edges: the flip replaces the two triangles of e, which changes the SCF and
// the areas beside e and its four neighbours and nothing else; the four outer triangles' other
// edges keep both their triangles. So both gains read the same stencil (the records of e and
// its neighbours) and have the same ROI, the 2-region. The caller checks flipIsConvex first.
//   before: triangles (a, b, l) and (b, a, r)   after: (r, b, l) and (l, a, r)
DDT_FN double scfFlipGain(FlipStencil s, StencilValues z, Places places, bool face_weighted) {
    if (stencilIsFlat(s, z)) return 0.0;
    Gradient left = planeGradient(s.a, s.b, s.l, z.a, z.b, z.l, places);
    Gradient right = planeGradient(s.b, s.a, s.r, z.b, z.a, z.r, places);
    Gradient new_rbl = planeGradient(s.r, s.b, s.l, z.r, z.b, z.l, places);
    Gradient new_lar = planeGradient(s.l, s.a, s.r, z.l, z.a, z.r, places);
    bool w = face_weighted;
    // Each outer triangle lies across one neighbour edge, listed in positive orientation.
    DDT_PRECISE double before = pairCost(left, right, w) +
                                neighbourCost(left, s.l, s.b, s.far_bl, z.l, z.b, z.far_bl, places, w) +
                                neighbourCost(left, s.a, s.l, s.far_la, z.a, z.l, z.far_la, places, w) +
                                neighbourCost(right, s.r, s.a, s.far_ar, z.r, z.a, z.far_ar, places, w) +
                                neighbourCost(right, s.b, s.r, s.far_rb, z.b, z.r, z.far_rb, places, w);
    DDT_PRECISE double after = pairCost(new_rbl, new_lar, w) +
                               neighbourCost(new_rbl, s.l, s.b, s.far_bl, z.l, z.b, z.far_bl, places, w) +
                               neighbourCost(new_lar, s.a, s.l, s.far_la, z.a, z.l, z.far_la, places, w) +
                               neighbourCost(new_lar, s.r, s.a, s.far_ar, z.r, z.a, z.far_ar, places, w) +
                               neighbourCost(new_rbl, s.b, s.r, s.far_rb, z.b, z.r, z.far_rb, places, w);
    return before - after;
}

// Sederberg's flip gain (scfFlipGain without weights).
DDT_FN double flipGain(FlipStencil s, StencilValues z, Places places) { return scfFlipGain(s, z, places, false); }

#ifdef __cplusplus
}  // namespace ddt
#endif
#undef DDT_FN
#undef DDT_PRECISE
#endif
