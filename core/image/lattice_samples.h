// The samples of a lattice triangle at exactly three output pixels per input pixel, without
// scanning: a render at exactly ×3 (and locateSamples there) finds them this way. (The
// consistent reconstruction's supersamples, at the same places, need no locating at all:
// core/image/supersample_lattice.h.)
//
// In a triangulation of the pixel grid every pixel centre is a vertex, so no lattice point
// lies inside a triangle or on an edge but its corners, and by Pick's theorem twice its area
// is 1 (unimodular). Its affine map from the unit triangle is then an integer matrix of
// determinant 1, which maps the thirds of the plane onto the thirds: the samples at ×3 (which
// lie on the thirds, glsl/raster.h) that a unimodular triangle can hold are its ten points of
// barycentric weights (i, j, l) / 3, i + j + l = 3: the centroid, two points on each edge and
// the corners. Which of them it owns is raster.h's tie rule, applied to the one edge a point
// lies on (or the two, at a corner); the weights are exact thirds. Triangles on the hull,
// where samples are clamped, are scanned as before. The output is the same,
// bit for bit, as scanning the triangle (test/image/test_lattice_samples.cpp).
#pragma once

#include <algorithm>
#include <cstdint>

namespace ddt {

// Calls sample(X, Y, l0, l1, l2) for the samples of output columns [x_begin, x_end) and rows
// [y_begin, y_end) of a 3 in_w × 3 in_h output that the triangle with vertices (x[m], y[m])
// (input pixels, positive orientation) owns, in row-major order. Returns false, calling
// nothing, if twice the triangle's area is not 1 or it touches the hull: the caller scans it.
template <typename Sample>
bool visitLatticeTriangle(const uint32_t x[3], const uint32_t y[3], uint32_t in_w, uint32_t in_h, uint32_t x_begin,
                          uint32_t x_end, uint32_t y_begin, uint32_t y_end, const Sample& sample) {
    const int64_t ex[3] = {int64_t(x[2]) - x[1], int64_t(x[0]) - x[2], int64_t(x[1]) - x[0]};  // edge m: m+1 → m+2
    const int64_t ey[3] = {int64_t(y[2]) - y[1], int64_t(y[0]) - y[2], int64_t(y[1]) - y[0]};
    if (ex[1] * ey[2] - ey[1] * ex[2] != 1) return false;  // twice the signed area
    // On the hull, samples are clamped onto its lines and pushed backwards on its last column
    // and row: those triangles, a thin ring, are left to the scan.
    if (std::min({x[0], x[1], x[2]}) == 0 || std::max({x[0], x[1], x[2]}) == in_w - 1 ||
        std::min({y[0], y[1], y[2]}) == 0 || std::max({y[0], y[1], y[2]}) == in_h - 1)
        return false;
    // Elsewhere a point on edge m's line counts as inside when the push of raster.h's
    // sampleSide, (+ε, +ε²), moves it into the triangle. Each point is one sample: the centroid
    // always, an edge's two points by the edge's tie, a corner by both of its edges'.
    bool tie[3];
    for (int m = 0; m < 3; ++m) tie[m] = ey[m] != 0 ? ey[m] < 0 : ex[m] > 0;
    struct Hit {
        uint64_t key;  // Y · 2^32 + X: row-major order
        uint8_t l[3];  // thirds
    };
    Hit hits[10];
    int count = 0;
    auto point = [&](uint8_t l0, uint8_t l1, uint8_t l2) {
        // Three times the point's coordinates, plus 1, is its sample (raster.h at out = 3 in).
        const uint32_t X = l0 * x[0] + l1 * x[1] + l2 * x[2] + 1, Y = l0 * y[0] + l1 * y[1] + l2 * y[2] + 1;
        if (X < x_begin || X >= x_end || Y < y_begin || Y >= y_end) return;
        const Hit hit{uint64_t(Y) << 32 | X, {l0, l1, l2}};
        int n = count++;
        for (; n > 0 && hits[n - 1].key > hit.key; --n) hits[n] = hits[n - 1];
        hits[n] = hit;
    };
    point(1, 1, 1);
    if (tie[0]) point(0, 1, 2), point(0, 2, 1);
    if (tie[1]) point(1, 0, 2), point(2, 0, 1);
    if (tie[2]) point(1, 2, 0), point(2, 1, 0);
    if (tie[1] && tie[2]) point(3, 0, 0);
    if (tie[2] && tie[0]) point(0, 3, 0);
    if (tie[0] && tie[1]) point(0, 0, 3);
    // The weights as the scan's division of exact integers gives them: the doubles nearest to the thirds.
    constexpr double kThirds[4] = {0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0};
    for (int n = 0; n < count; ++n)
        sample(uint32_t(hits[n].key), uint32_t(hits[n].key >> 32), kThirds[hits[n].l[0]], kThirds[hits[n].l[1]],
               kThirds[hits[n].l[2]]);
    return true;
}

}  // namespace ddt
