// The samples of a lattice triangle at exactly three output pixels per input pixel, without
// scanning: the consistent reconstruction locates its supersamples this way (kSupersampling).
//
// In a triangulation of the pixel grid every pixel centre is a vertex, so no lattice point
// lies inside a triangle or on an edge but its corners, and by Pick's theorem twice its area
// is 1 (unimodular). Its affine map from the unit triangle is then an integer matrix of
// determinant 1, which maps the thirds of the plane onto the thirds: the samples at ×3 (which
// lie on the thirds, glsl/raster.h) that a unimodular triangle can hold are its ten points of
// barycentric weights (i, j, l) / 3, i + j + l = 3: the centroid, two points on each edge and
// the corners. Which of them it owns is raster.h's tie rule, applied to the one edge a point
// lies on (or the two, at a corner); the weights are exact thirds. The output is the same,
// bit for bit, as scanning the triangle (test/image/test_lattice_samples.cpp).
#pragma once

#include <algorithm>
#include <cstdint>

namespace ddt {

// Calls sample(X, Y, l0, l1, l2) for the samples of output columns [x_begin, x_end) and rows
// [y_begin, y_end) of a 3 in_w × 3 in_h output that the triangle with vertices (x[m], y[m])
// (input pixels, positive orientation) owns, in row-major order. Returns false, calling
// nothing, if twice the triangle's area is not 1: the caller scans it.
template <typename Sample>
bool visitLatticeTriangle(const uint32_t x[3], const uint32_t y[3], uint32_t in_w, uint32_t in_h, uint32_t x_begin,
                          uint32_t x_end, uint32_t y_begin, uint32_t y_end, Sample sample) {
    const int64_t ex[3] = {int64_t(x[2]) - x[1], int64_t(x[0]) - x[2], int64_t(x[1]) - x[0]};  // edge m: m+1 → m+2
    const int64_t ey[3] = {int64_t(y[2]) - y[1], int64_t(y[0]) - y[2], int64_t(y[1]) - y[0]};
    if (ex[1] * ey[2] - ey[1] * ex[2] != 1) return false;  // twice the signed area
    // Whether a point on edge m's line counts as inside, pushed by (dir_u·ε, dir_v·ε²) as in
    // raster.h's sampleSide: dir is −1 on the hull's last column or row, +1 elsewhere.
    auto tieInside = [&](int m, int dir_u, int dir_v) { return ey[m] != 0 ? -ey[m] * dir_u > 0 : ex[m] * dir_v > 0; };
    struct Hit {
        uint64_t key;  // Y · 2^32 + X: row-major order
        uint8_t l[3];  // thirds
    };
    Hit hits[40];  // ten points, a corner point of the image at most four times
    int count = 0;
    auto add = [&](uint32_t X, uint32_t Y, const uint8_t l[3]) {
        if (X < x_begin || X >= x_end || Y < y_begin || Y >= y_end) return;
        const Hit hit{uint64_t(Y) << 32 | X, {l[0], l[1], l[2]}};
        int n = count++;
        for (; n > 0 && hits[n - 1].key > hit.key; --n) hits[n] = hits[n - 1];
        hits[n] = hit;
    };
    const bool on_hull = std::min({x[0], x[1], x[2]}) == 0 || std::max({x[0], x[1], x[2]}) == in_w - 1 ||
                         std::min({y[0], y[1], y[2]}) == 0 || std::max({y[0], y[1], y[2]}) == in_h - 1;
    if (!on_hull) {
        // Away from the hull every push is (+ε, +ε²), and each point is one sample: the
        // centroid always, an edge's two points by the edge's tie, a corner by both of its edges'.
        const bool tie[3] = {tieInside(0, 1, 1), tieInside(1, 1, 1), tieInside(2, 1, 1)};
        auto point = [&](uint8_t l0, uint8_t l1, uint8_t l2) {
            const uint8_t l[3] = {l0, l1, l2};
            add(l0 * x[0] + l1 * x[1] + l2 * x[2] + 1, l0 * y[0] + l1 * y[1] + l2 * y[2] + 1, l);
        };
        point(1, 1, 1);
        if (tie[0]) point(0, 1, 2), point(0, 2, 1);
        if (tie[1]) point(1, 0, 2), point(2, 0, 1);
        if (tie[2]) point(1, 2, 0), point(2, 1, 0);
        if (tie[1] && tie[2]) point(3, 0, 0);
        if (tie[2] && tie[0]) point(0, 3, 0);
        if (tie[0] && tie[1]) point(0, 0, 3);
    } else {
        for (uint8_t i = 0; i <= 3; ++i)
            for (uint8_t j = 0; i + j <= 3; ++j) {
                const uint8_t l[3] = {i, j, uint8_t(3 - i - j)};
                // Three times the point's coordinates: its sample is 3x + 1 (raster.h at out = 3 in).
                const uint32_t tx = l[0] * x[0] + l[1] * x[1] + l[2] * x[2], ty = l[0] * y[0] + l[1] * y[1] + l[2] * y[2];
                const int dir_u = tx == 3 * (in_w - 1) ? -1 : 1, dir_v = ty == 3 * (in_h - 1) ? -1 : 1;
                bool inside = true;
                for (int m = 0; m < 3 && inside; ++m)
                    if (l[m] == 0) inside = tieInside(m, dir_u, dir_v);
                if (!inside) continue;
                // Samples outside the hull are clamped onto its edge: the first and last column
                // (row) hold copies of the points on the hull's first and last line.
                const uint32_t X_last = tx == 3 * (in_w - 1) ? 3 * in_w - 1 : tx + 1;
                const uint32_t Y_last = ty == 3 * (in_h - 1) ? 3 * in_h - 1 : ty + 1;
                for (uint32_t Y = ty == 0 ? 0 : ty + 1; Y <= Y_last; ++Y)
                    for (uint32_t X = tx == 0 ? 0 : tx + 1; X <= X_last; ++X) add(X, Y, l);
            }
    }
    // The weights as the scan's division of exact integers gives them: the doubles nearest to the thirds.
    constexpr double kThirds[4] = {0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0};
    for (int n = 0; n < count; ++n)
        sample(uint32_t(hits[n].key), uint32_t(hits[n].key >> 32), kThirds[hits[n].l[0]], kThirds[hits[n].l[1]],
               kThirds[hits[n].l[2]]);
    return true;
}

}  // namespace ddt
