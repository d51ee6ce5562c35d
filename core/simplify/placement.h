// Where a collapse puts the merged vertex, and what it costs there: Garland and Heckbert's
// optimal placement, on a mesh with explicit positions (core/image/mesh.h).
//
// The merged quadric (the sum of the two vertices') is least at one point of position and
// colour when it is regular. Its place is used where the rectangle allows it:
// - `from` and `to` both interior: the point of least Q over position and colour (the same
//   for both directions of the edge);
// - `to` on one side of the rectangle (not a corner), `from` inside or on the same side: the
//   point of least Q on that side's line, its other coordinate and the colour free;
// - else (`to` a corner, or on a locked side: edge_collapse.h): `to`'s place.
// The place is snapped to the fixed-point grid (1/1024 pixel), must be legal (canCollapse: no
// fold-over, the sides kept) and must cost no more than `to`'s place; otherwise, or where the
// quadric is singular in the free axes (a flat region, whose planes leave the position
// undetermined), the merged vertex stays at `to`'s place, Garland and Heckbert's fallback to
// the better endpoint (the other direction is the other endpoint). The cost is Q at the place
// with the colour that is best there, the start of the vertex's final colour
// (setVertexColours); a place where no colour is best (vertical planes, none of a picture's)
// is not taken.
#pragma once

#include <array>

#include "edge_collapse.h"
#include "vertex_quadrics.h"

namespace ddt {

struct PlacedCollapse {
    Collapse collapse;  // moves, with its target, when the merged vertex leaves `to`'s place
    double cost = 0.0;
};

// Edge `edge`'s two collapses placed: [0] a into b, [1] b into a. `merged` is the two
// vertices' quadric summed. The endpoint collapses are not checked for legality here.
std::array<PlacedCollapse, 2> placeCollapses(const Mesh& mesh, const VertexEdges& edges, const QuadricPoints& points,
                                             const Quadric& merged, uint32_t edge);

}  // namespace ddt
