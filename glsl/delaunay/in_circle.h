// The perturbed in-circle test of core/delaunay/predicates.h, written once in the common
// subset of C++ and GLSL (GLSL needs GL_EXT_shader_explicit_arithmetic_types_int64 first), for
// the device's flips (compute/delaunay/). GLSL has no 128-bit integers, so the determinant's
// three products are formed from 32-bit halves in 64-bit words and summed as two 64-bit words.
//
// Headroom, for coordinates in [0, 2^26) (differences |δ| < 2^27, as predicates.h allows):
// each lift δx² + δy² < 2^55, each minor |orient| < 2^55 — both exact in int64, as in
// predicates.h. A product of two factors below 2^55: with x = x1 · 2^32 + x0 (x1 < 2^23), x0 · y0
// < 2^64, the middle x0 · y1 + x1 · y0 < 2^56 and x1 · y1 < 2^46, each exact in uint64; the
// product is below 2^110. The determinant is (sum of the positive products) − (sum of the
// negative ones), each sum of at most three below 2^112: two unsigned 128-bit sums that never
// wrap, compared word by word, and no signed 128-bit arithmetic at all.
#ifndef DDTUP_IN_CIRCLE_H
#define DDTUP_IN_CIRCLE_H

#include "../fixed_position.h"

#ifdef __cplusplus
namespace ddt {
#define DDT_FN inline
#else
#define DDT_FN
#endif

// An unsigned 128-bit integer: high · 2^64 + low.
struct WideUnsigned {
    uint64_t high;
    uint64_t low;
};

// x · y, exact, for x, y < 2^55 (above).
DDT_FN WideUnsigned wideProduct(uint64_t x, uint64_t y) {
    const uint64_t half_mask = uint64_t(0xFFFFFFFFu);
    const uint64_t x0 = x & half_mask, x1 = x >> 32, y0 = y & half_mask, y1 = y >> 32;
    const uint64_t low_part = x0 * y0;
    const uint64_t middle = x0 * y1 + x1 * y0;
    WideUnsigned w;
    w.low = low_part + (middle << 32);
    w.high = x1 * y1 + (middle >> 32) + uint64_t(w.low < low_part ? 1u : 0u);
    return w;
}

// p + q, for sums below 2^128.
DDT_FN WideUnsigned wideSum(WideUnsigned p, WideUnsigned q) {
    WideUnsigned s;
    s.low = p.low + q.low;
    s.high = p.high + q.high + uint64_t(s.low < p.low ? 1u : 0u);
    return s;
}

// The sign of predicates.h's inCircleDeterminant(a, b, c, d): +1, 0 or −1, exact. The same
// expansion: lift_a · orient(d, b, c) + lift_b · orient(a, d, c) + lift_c · orient(a, b, d).
DDT_FN int inCircleSign(Position a, Position b, Position c, Position d) {
    const int64_t adx = int64_t(a.x) - int64_t(d.x), ady = int64_t(a.y) - int64_t(d.y);
    const int64_t bdx = int64_t(b.x) - int64_t(d.x), bdy = int64_t(b.y) - int64_t(d.y);
    const int64_t cdx = int64_t(c.x) - int64_t(d.x), cdy = int64_t(c.y) - int64_t(d.y);
    const uint64_t lift_a = uint64_t(adx * adx + ady * ady);
    const uint64_t lift_b = uint64_t(bdx * bdx + bdy * bdy);
    const uint64_t lift_c = uint64_t(cdx * cdx + cdy * cdy);
    const int64_t minor_a = bdx * cdy - bdy * cdx;
    const int64_t minor_b = cdx * ady - cdy * adx;
    const int64_t minor_c = adx * bdy - ady * bdx;
    const WideUnsigned term_a = wideProduct(lift_a, uint64_t(minor_a < 0 ? -minor_a : minor_a));
    const WideUnsigned term_b = wideProduct(lift_b, uint64_t(minor_b < 0 ? -minor_b : minor_b));
    const WideUnsigned term_c = wideProduct(lift_c, uint64_t(minor_c < 0 ? -minor_c : minor_c));
    WideUnsigned zero;
    zero.high = uint64_t(0u);
    zero.low = uint64_t(0u);
    const WideUnsigned positive =
        wideSum(wideSum(minor_a > 0 ? term_a : zero, minor_b > 0 ? term_b : zero), minor_c > 0 ? term_c : zero);
    const WideUnsigned negative =
        wideSum(wideSum(minor_a < 0 ? term_a : zero, minor_b < 0 ? term_b : zero), minor_c < 0 ? term_c : zero);
    if (positive.high != negative.high) return positive.high > negative.high ? 1 : -1;
    if (positive.low != negative.low) return positive.low > negative.low ? 1 : -1;
    return 0;
}

// predicates.h's outranks: the symbolic priority, larger x − y first, then larger x.
DDT_FN bool positionOutranks(Position p, Position q) {
    const int64_t p_key = int64_t(p.x) - int64_t(p.y), q_key = int64_t(q.x) - int64_t(q.y);
    return p_key != q_key ? p_key > q_key : p.x > q.x;
}

// predicates.h's inCircle, the same decisions in the same order: d strictly inside the
// circumcircle of the positive triangle (a, b, c), ties broken symbolically (the reasoning is
// there).
DDT_FN bool inCirclePerturbed(Position a, Position b, Position c, Position d) {
    const int sign = inCircleSign(a, b, c, d);
    if (sign != 0) return sign > 0;
    if (positionOutranks(a, b) && positionOutranks(a, c) && positionOutranks(a, d))
        return positionOrient(d.x, d.y, b.x, b.y, c.x, c.y) > 0;
    if (positionOutranks(b, c) && positionOutranks(b, d)) return positionOrient(a.x, a.y, d.x, d.y, c.x, c.y) > 0;
    if (positionOutranks(c, d)) return positionOrient(a.x, a.y, b.x, b.y, d.x, d.y) > 0;
    return false;  // d is the top: raised above the circle's plane
}

#ifdef __cplusplus
}  // namespace ddt
#endif
#undef DDT_FN
#endif
