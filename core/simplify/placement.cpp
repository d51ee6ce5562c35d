#include "placement.h"

#include <array>
#include <bit>
#include <cmath>

namespace ddt {

namespace {

// Q at position p with the colour that is best there (the vertex's own if Q is singular in
// the colour axes, which needs vertical planes: none of a picture's).
double costAt(const QuadricPoints& points, const Quadric& merged, Position p, uint32_t colour_of) {
    double point[kMaxQuadricDimensions];
    points.of(colour_of, point);
    QuadricPoints::at(p, point);
    merged.minimiseFree(point, points.colourAxes(), points.n);
    return merged.at(point, points.n);
}

// A point's position coordinate (pixels × kPositionWeight) on the fixed-point grid, or −1 if
// it is not finite or lies off the rectangle's [0, side − 1].
int64_t snapped(double coordinate, uint32_t side) {
    const double fixed = std::nearbyint(coordinate / kPositionWeight * kPositionOne);
    if (!(fixed >= 0.0 && fixed <= double(side - 1) * kPositionOne)) return -1;
    return int64_t(fixed);
}

// The merged vertex of e's collapse at the quadric's least point with the axes `free` (the
// others from `to`'s point), snapped; moves = false where there is none, it is `to`'s place or
// it is not legal. The cost is Q there with the best colour, which must exist.
PlacedCollapse moveTo(const Mesh& mesh, const VertexEdges& edges, const QuadricPoints& points, const Quadric& merged,
                      Collapse collapse, uint32_t free) {
    const uint32_t to = collapse.to(mesh);
    PlacedCollapse none{collapse, 0.0};
    double point[kMaxQuadricDimensions];
    points.of(to, point);
    if (!merged.minimiseFree(point, free, points.n)) return none;
    const int64_t x = snapped(point[0], mesh.width), y = snapped(point[1], mesh.height);
    if (x < 0 || y < 0) return none;
    Collapse moved = collapse;
    moved.moves = true;
    moved.target = {int32_t(x), int32_t(y)};
    if (moved.target == positionOf(mesh, to) || !canCollapse(mesh, edges, moved)) return none;
    QuadricPoints::at(moved.target, point);
    if (!merged.minimiseFree(point, points.colourAxes(), points.n)) return none;
    return {moved, merged.at(point, points.n)};
}

}  // namespace

std::array<PlacedCollapse, 2> placeCollapses(const Mesh& mesh, const VertexEdges& edges, const QuadricPoints& points,
                                             const Quadric& merged, uint32_t edge) {
    std::array<PlacedCollapse, 2> placed;
    const uint32_t a = mesh.vertices[edge].a, b = mesh.vertices[edge].b;
    const uint32_t sides[2] = {collapseSides(mesh, a), collapseSides(mesh, b)};
    const bool explicit_positions = !mesh.positions.empty();
    // Both inside: all axes free, so the least point, its legality (the triangles around both
    // ends) and its cost are the same either way.
    PlacedCollapse inside{};
    if (explicit_positions && sides[0] == 0 && sides[1] == 0)
        inside = moveTo(mesh, edges, points, merged, {edge, true}, points.allAxes());
    for (int direction = 0; direction < 2; ++direction) {
        const Collapse collapse{edge, direction == 1};
        const uint32_t from_sides = sides[direction == 1 ? 1 : 0], to_sides = sides[direction == 1 ? 0 : 1];
        const uint32_t to = collapse.to(mesh);
        const PlacedCollapse stays{collapse, costAt(points, merged, positionOf(mesh, to), to)};
        PlacedCollapse moved{};
        if (inside.collapse.moves) {
            moved = inside;
            moved.collapse.b_into_a = collapse.b_into_a;
        } else if (explicit_positions && std::popcount(to_sides) == 1 && (from_sides == 0 || from_sides == to_sides)) {
            // Along a side: the coordinate across it stays.
            moved = moveTo(mesh, edges, points, merged, collapse, points.allAxes() & (to_sides & 3 ? ~1u : ~2u));
        }
        placed[direction] = moved.collapse.moves && moved.cost <= stays.cost ? moved : stays;
    }
    return placed;
}

}  // namespace ddt
