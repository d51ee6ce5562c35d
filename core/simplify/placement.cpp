#include "placement.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

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

// The point's position coordinate k on the fixed-point grid, or −1 if it is not finite or
// lies off the rectangle's [0, side − 1].
int64_t snapped(double coordinate, uint32_t side) {
    const double fixed = std::nearbyint(coordinate / kPositionWeight * kPositionOne);
    if (!(fixed >= 0.0 && fixed <= double(side - 1) * kPositionOne)) return -1;
    return int64_t(fixed);
}

}  // namespace

PlacedCollapse placeCollapse(const Mesh& mesh, const VertexEdges& edges, const QuadricPoints& points,
                             const Quadric& merged, Collapse collapse) {
    const uint32_t from = collapse.from(mesh), to = collapse.to(mesh);
    collapse.moves = false;
    PlacedCollapse result{collapse, costAt(points, merged, positionOf(mesh, to), to)};
    if (mesh.positions.empty()) return result;
    const uint32_t from_sides = rectangleSides(mesh, from), to_sides = rectangleSides(mesh, to);
    uint32_t free = points.allAxes();
    if (from_sides != 0 || to_sides != 0) {
        // Along a side: the coordinate across it stays.
        if (std::popcount(to_sides) != 1 || (from_sides != 0 && from_sides != to_sides)) return result;
        free &= to_sides & 3 ? ~1u : ~2u;
    }
    double point[kMaxQuadricDimensions];
    points.of(to, point);
    if (!merged.minimiseFree(point, free, points.n)) return result;
    const int64_t x = snapped(point[0], mesh.width), y = snapped(point[1], mesh.height);
    if (x < 0 || y < 0) return result;
    Collapse moved = collapse;
    moved.moves = true;
    moved.target = {int32_t(x), int32_t(y)};
    if (moved.target == positionOf(mesh, to) || !canCollapse(mesh, edges, moved)) return result;
    const double cost = costAt(points, merged, moved.target, to);
    if (!(cost <= result.cost)) return result;  // snapping lost more than the place gained
    return {moved, cost};
}

}  // namespace ddt
