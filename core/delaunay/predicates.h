// The exact predicates of the Delaunay triangulation (core/delaunay/delaunay.h): orientation
// and in-circle on fixed-point positions (glsl/fixed_position.h), with a symbolic tie-break
// for four cocircular points, so that every question has a yes-or-no answer and the
// triangulation is unique.
//
// Range: coordinates in [0, 2^26) (frames of at most kMaxDelaunaySide = 65 536 pixels a side
// at kPositionOne = 1024), so every coordinate difference lies in (−2^26, 2^26); the bounds
// below allow differences up to 2^27.
#pragma once

#include <cstdint>

#include "fixed_position.h"
#include "mesh.h"

namespace ddt {

// Twice the signed area of (p, q, r): > 0 for a positive triangle (core/image/mesh.h). Exact in int64.
inline int64_t orient(Position p, Position q, Position r) { return positionOrient(p.x, p.y, q.x, q.y, r.x, r.y); }

// The symbolic priority of the tie-break: larger x − y first, then larger x. A total order on
// distinct positions. In every unit grid cell the corner (x + 1, y) comes first, so the cell
// is cut by the other diagonal, (x, y)–(x + 1, y + 1): the grid's own triangulation.
inline bool outranks(Position p, Position q) {
    const int64_t p_key = int64_t(p.x) - p.y, q_key = int64_t(q.x) - q.y;
    return p_key != q_key ? p_key > q_key : p.x > q.x;
}

// The in-circle determinant, > 0 iff d lies strictly inside the circumcircle of the positive
// triangle (a, b, c), 0 iff the four points are cocircular:
//
//     | adx  ady  adx² + ady² |
//     | bdx  bdy  bdx² + bdy² |      with adx = a.x − d.x, …
//     | cdx  cdy  cdx² + cdy² |
//
// expanded along its last column: lift_a · orient(d, b, c) + lift_b · orient(a, d, c) +
// lift_c · orient(a, b, d) (each 2×2 minor is one of these orients). Headroom, for
// differences |δ| < 2^27: each lift δx² + δy² < 2^55 and each minor < 2 · 2^54 = 2^55, both
// exact in int64; each product < 2^110 and the sum of three < 2^112, exact in __int128.
inline __int128 inCircleDeterminant(Position a, Position b, Position c, Position d) {
    const int64_t adx = int64_t(a.x) - d.x, ady = int64_t(a.y) - d.y;
    const int64_t bdx = int64_t(b.x) - d.x, bdy = int64_t(b.y) - d.y;
    const int64_t cdx = int64_t(c.x) - d.x, cdy = int64_t(c.y) - d.y;
    const int64_t lift_a = adx * adx + ady * ady;
    const int64_t lift_b = bdx * bdx + bdy * bdy;
    const int64_t lift_c = cdx * cdx + cdy * cdy;
    const int64_t minor_a = bdx * cdy - bdy * cdx;  // orient(d, b, c)
    const int64_t minor_b = cdx * ady - cdy * adx;  // orient(a, d, c)
    const int64_t minor_c = adx * bdy - ady * bdx;  // orient(a, b, d)
    return __int128(lift_a) * minor_a + __int128(lift_b) * minor_b + __int128(lift_c) * minor_c;
}

// Whether d lies inside the circumcircle of the positive triangle (a, b, c), exactly, with
// ties (four cocircular points) broken by Simulation of Simplicity on the lifted coordinate:
// the lift |p|² of each point is raised by an infinitesimal, the one of a higher-priority
// point (outranks) dominating all of those below it, so only the highest-priority point of
// {a, b, c, d} decides. The determinant is the lifted d's height below the plane through the
// lifted a, b, c. Raising d lifts it above that plane: d is outside. Raising a vertex of abc
// raises the plane at d by that vertex's barycentric coordinate of d times the infinitesimal,
// whose sign is the orient with the vertex replaced by d — never 0 here, since three distinct
// cocircular points are not collinear. One consistent perturbation of all lifts keeps the
// answers consistent between triangles, and since every lifted point stays on the strictly
// convex paraboloid's lower hull, the perturbed Delaunay triangulation is unique.
inline bool inCircle(Position a, Position b, Position c, Position d) {
    const __int128 det = inCircleDeterminant(a, b, c, d);
    if (det != 0) return det > 0;
    const bool a_top = outranks(a, b) && outranks(a, c) && outranks(a, d);
    if (a_top) return orient(d, b, c) > 0;
    const bool b_top = outranks(b, c) && outranks(b, d);
    if (b_top) return orient(a, d, c) > 0;
    if (outranks(c, d)) return orient(a, b, d) > 0;
    return false;  // d is the top: raised above the circle's plane
}

}  // namespace ddt
