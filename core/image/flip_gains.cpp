#include "flip_gains.h"

#include <cassert>
#include <limits>

namespace ddt {

namespace {

// A vertex of a stencil: its id and the coordinates planeGradient derives from it: its pixel
// centre (x, y) on the grid, or its explicit position in fixed point.
struct Corner {
    uint32_t id;
    int32_t x, y;
};

// What planeGradient computes from the vertices alone: the triangle turned so that its smallest
// id comes first (orientation kept), and triangleSides' coordinate differences and twice area.
struct TriangleShape {
    int first;  // which corner comes first after the turn: 0, 1 or 2
    double dx1, dy1, dx2, dy2, scale;
};

// triangleSides (glsl/image/sederberg.h) of corners given as coordinates, with the same operations:
// on the grid differences of integers and their exact products, with explicit positions
// fixed-point differences times 1 / kPositionOne and positionOrient's exact area. The places
// are a template argument, so that the grid's path tests no flag per corner or triangle.
template <bool positioned>
inline TriangleShape turnedShape(int first, const Corner& c0, const Corner& c1, const Corner& c2) {
    if constexpr (positioned) {
        const double unit = 1.0 / double(kPositionOne);
        const double dx1 = double(c1.x - c0.x) * unit, dy1 = double(c1.y - c0.y) * unit;
        const double dx2 = double(c2.x - c0.x) * unit, dy2 = double(c2.y - c0.y) * unit;
        const int64_t twice_area = positionOrient(c0.x, c0.y, c1.x, c1.y, c2.x, c2.y);
        return {first, dx1, dy1, dx2, dy2, double(twice_area) * (unit * unit)};
    }
    const double dx1 = c1.x - c0.x, dy1 = c1.y - c0.y, dx2 = c2.x - c0.x, dy2 = c2.y - c0.y;
    return {first, dx1, dy1, dx2, dy2, dx1 * dy2 - dx2 * dy1};
}

template <bool positioned>
inline Corner cornerOf(uint32_t id, const DivideBy& by_width, const Position* positions) {
    if constexpr (positioned) return {id, positions[id].x, positions[id].y};
    return {id, int32_t(by_width.remainder(id)), int32_t(by_width.quotient(id))};
}

template <bool positioned>
inline TriangleShape shapeOf(const Corner& p0, const Corner& p1, const Corner& p2) {
    if (p1.id < p0.id && p1.id < p2.id) return turnedShape<positioned>(1, p1, p2, p0);
    if (p2.id < p0.id && p2.id < p1.id) return turnedShape<positioned>(2, p2, p0, p1);
    return turnedShape<positioned>(0, p0, p1, p2);
}

// planeGradient of the triangle with values z0, z1, z2 at its corners (in the order given to shapeOf).
inline Gradient gradientOf(const TriangleShape& s, float z0, float z1, float z2) {
    const float first = s.first == 0 ? z0 : s.first == 1 ? z1 : z2;
    const float second = s.first == 0 ? z1 : s.first == 1 ? z2 : z0;
    const float third = s.first == 0 ? z2 : s.first == 1 ? z0 : z1;
    const double dz1 = double(second) - double(first), dz2 = double(third) - double(first);
    return {dz1 * s.dy2 - dz2 * s.dy1, dz2 * s.dx1 - dz1 * s.dx2, s.scale};
}

// varianceShare of the triangle (p0, p1, p2) with values z0..z2, turned as varianceCost turns it.
inline double varianceOf(const TriangleShape& s, float z0, float z1, float z2) {
    const float first = s.first == 0 ? z0 : s.first == 1 ? z1 : z2;
    const float second = s.first == 0 ? z1 : s.first == 1 ? z2 : z0;
    const float third = s.first == 0 ? z2 : s.first == 1 ? z0 : z1;
    return varianceShare(s.scale, first, second, third);
}

}  // namespace

FlipGains::FlipGains(const Mesh& mesh, const CostField& field, CostFunction cost)
    : mesh_(mesh), field_(field), cost_(cost), by_width_(mesh.width), positions_(placesOf(mesh).positions) {
    channels_.push_back({field.luma, {}, {}});
    if (!field.alpha.empty()) channels_.push_back({field.alpha, {}, {}});
    if (cost_ == CostFunction::variance) return;  // nothing to keep
    const bool face_weighted = cost_ == CostFunction::face_scf;
    for (Channel& channel : channels_) channel.costs.resize(mesh.edgeCount());
    if (positions_) keepCosts<true>(face_weighted);
    else keepCosts<false>(face_weighted);
}

template <bool positioned>
void FlipGains::keepCosts(bool face_weighted) {
    auto corner = [&](uint32_t id) { return cornerOf<positioned>(id, by_width_, positions_); };
    for (uint32_t e = 0; e < mesh_.edgeCount(); ++e) {
        const EdgeVertices& v = mesh_.vertices[e];
        if (v.l == kNone || v.r == kNone) {
            for (Channel& channel : channels_) channel.costs[e] = 0.0;
            continue;
        }
        // edgeCost's: the pairCost of the left triangle (a, b, l) and the right one (b, a, r).
        const Corner a = corner(v.a), b = corner(v.b), l = corner(v.l), r = corner(v.r);
        const TriangleShape left = shapeOf<positioned>(a, b, l), right = shapeOf<positioned>(b, a, r);
        for (Channel& channel : channels_) {
            const std::vector<float>& z = channel.values;
            channel.costs[e] = pairCost(gradientOf(left, z[v.a], z[v.b], z[v.l]),
                                        gradientOf(right, z[v.b], z[v.a], z[v.r]), face_weighted);
        }
    }
}

double FlipGains::total() const {
    // Variance keeps no shares: its total from scratch, once per optimisation at each end.
    if (cost_ == CostFunction::variance) return meshCost(mesh_, field_, cost_);
    // meshCost's sum: edge by edge in id order, each edge's channels first.
    double total = 0.0;
    for (uint32_t e = 0; e < mesh_.edgeCount(); ++e) {
        double cost = channels_[0].costs[e];
        if (channels_.size() > 1) cost += channels_[1].costs[e];
        total += cost;
    }
    return total;
}

double FlipGains::gainOf(uint32_t e) {
    changed_[0] = kNone;
    const EdgeVertices& v = mesh_.vertices[e];
    if (v.l == kNone || v.r == kNone) return -std::numeric_limits<double>::infinity();
    if (cost_ == CostFunction::variance) return positions_ ? varianceGainOf<true>(e) : varianceGainOf<false>(e);
    return positions_ ? scfGainOf<true>(e) : scfGainOf<false>(e);
}

template <bool positioned>
double FlipGains::scfGainOf(uint32_t e) {
    const EdgeVertices& v = mesh_.vertices[e];
    const bool face_weighted = cost_ == CostFunction::face_scf;
    auto corner = [&](uint32_t id) { return cornerOf<positioned>(id, by_width_, positions_); };
    const Corner a = corner(v.a), b = corner(v.b), l = corner(v.l), r = corner(v.r);
    // flipIsConvex: both new triangles positive (orientation's sign is exact).
    const TriangleShape rbl = shapeOf<positioned>(r, b, l), lar = shapeOf<positioned>(l, a, r);
    if (!(rbl.scale > 0.0 && lar.scale > 0.0)) return -std::numeric_limits<double>::infinity();

    const EdgeNeighbours& n = mesh_.neighbours[e];
    const uint32_t neighbours[4] = {n.bl, n.la, n.ar, n.rb};
    const uint32_t far_ids[4] = {farVertex(mesh_, n.bl, v.a), farVertex(mesh_, n.la, v.b), farVertex(mesh_, n.ar, v.b),
                                 farVertex(mesh_, n.rb, v.a)};
    // The outer triangles across the neighbours, in positive orientation: (l, b, far_bl),
    // (a, l, far_la), (r, a, far_ar), (b, r, far_rb); after the flip, bl and rb border the new
    // triangle (r, b, l), la and ar the new (l, a, r).
    const Corner* near[4][2] = {{&l, &b}, {&a, &l}, {&r, &a}, {&b, &r}};
    const int new_side[4] = {0, 1, 1, 0};  // 0: (r, b, l), 1: (l, a, r)
    Corner far[4];
    TriangleShape outer[4];
    for (int k = 0; k < 4; ++k)
        if (far_ids[k] != kNone) {
            far[k] = corner(far_ids[k]);
            outer[k] = shapeOf<positioned>(*near[k][0], *near[k][1], far[k]);
        }

    changed_[0] = e;
    for (int k = 0; k < 4; ++k) changed_[k + 1] = neighbours[k];
    double gain = 0.0;
    for (size_t ch = 0; ch < channels_.size(); ++ch) {
        Channel& channel = channels_[ch];
        const std::vector<float>& z = channel.values;
        const std::vector<double>& costs = channel.costs;
        const float za = z[v.a], zb = z[v.b], zl = z[v.l], zr = z[v.r];
        float zfar[4];
        for (int k = 0; k < 4; ++k) zfar[k] = far_ids[k] == kNone ? 0.0f : z[far_ids[k]];
        const StencilValues values = {za, zb, zl, zr, zfar[0], zfar[1], zfar[2], zfar[3]};
        const FlipStencil stencil = {v.a, v.b, v.l, v.r, far_ids[0], far_ids[1], far_ids[2], far_ids[3]};
        double channel_gain = 0.0;
        if (stencilIsFlat(stencil, values)) {
            // Every cost around is 0 and stays 0.
            for (double& cost : channel.after) cost = 0.0;
        } else {
            const Gradient inner[2] = {gradientOf(rbl, zr, zb, zl), gradientOf(lar, zl, za, zr)};
            channel.after[0] = pairCost(inner[0], inner[1], face_weighted);
            for (int k = 0; k < 4; ++k) {
                const float z0 = k == 0 ? zl : k == 1 ? za : k == 2 ? zr : zb;
                const float z1 = k == 0 ? zb : k == 1 ? zl : k == 2 ? za : zr;
                channel.after[k + 1] =
                    far_ids[k] == kNone
                        ? 0.0
                        : pairCost(inner[new_side[k]], gradientOf(outer[k], z0, z1, zfar[k]), face_weighted);
            }
            // scfFlipGain's sums, term by term: the costs now, then after the flip.
            const double before =
                costs[e] + costs[neighbours[0]] + costs[neighbours[1]] + costs[neighbours[2]] + costs[neighbours[3]];
            const double after =
                channel.after[0] + channel.after[1] + channel.after[2] + channel.after[3] + channel.after[4];
            channel_gain = before - after;
        }
        gain = ch == 0 ? channel_gain : gain + channel_gain;
    }
    return gain;
}

// varianceGain's sums over e's two triangles, now and after the flip, channel by channel as
// flipGainOf adds them; -infinity for a quadrilateral that is not strictly convex.
template <bool positioned>
double FlipGains::varianceGainOf(uint32_t e) const {
    const EdgeVertices& v = mesh_.vertices[e];
    auto corner = [&](uint32_t id) { return cornerOf<positioned>(id, by_width_, positions_); };
    const Corner a = corner(v.a), b = corner(v.b), l = corner(v.l), r = corner(v.r);
    const TriangleShape rbl = shapeOf<positioned>(r, b, l), lar = shapeOf<positioned>(l, a, r);
    if (!(rbl.scale > 0.0 && lar.scale > 0.0)) return -std::numeric_limits<double>::infinity();
    const TriangleShape abl = shapeOf<positioned>(a, b, l), bar = shapeOf<positioned>(b, a, r);
    double gain = 0.0;
    for (size_t ch = 0; ch < channels_.size(); ++ch) {
        const std::vector<float>& z = channels_[ch].values;
        const float za = z[v.a], zb = z[v.b], zl = z[v.l], zr = z[v.r];
        const double before = varianceOf(abl, za, zb, zl) + varianceOf(bar, zb, za, zr);
        const double after = varianceOf(rbl, zr, zb, zl) + varianceOf(lar, zl, za, zr);
        const double channel_gain = before - after;
        gain = ch == 0 ? channel_gain : gain + channel_gain;
    }
    return gain;
}

double FlipGains::flipped(uint32_t e) {
    if (cost_ == CostFunction::variance) return std::numeric_limits<double>::infinity();  // nothing kept
    assert(changed_[0] == e);
    (void)e;
    // Flipping e back would make the old triangles again, whose costs are the kept ones bit for
    // bit (a triangle's gradient does not depend on the edge that asks, pairCost is symmetric),
    // and take away the new ones. scfGainOf would sum them in its order for the flipped record,
    // whose neighbours (bl, la, ar, rb) are the old (la, ar, rb, bl): changed_ 2, 3, 4, 1.
    double back = 0.0;
    for (size_t ch = 0; ch < channels_.size(); ++ch) {
        Channel& channel = channels_[ch];
        double old[5];
        for (int k = 0; k < 5; ++k) old[k] = channel.costs[changed_[k]];
        const double before = channel.after[0] + channel.after[2] + channel.after[3] + channel.after[4] + channel.after[1];
        const double after = old[0] + old[2] + old[3] + old[4] + old[1];
        const double channel_back = before - after;
        back = ch == 0 ? channel_back : back + channel_back;
        for (int k = 0; k < 5; ++k) channel.costs[changed_[k]] = channel.after[k];
    }
    changed_[0] = kNone;
    return back;
}

}  // namespace ddt
