// At exactly ×3 the renderer takes a grid mesh's samples from lattice_samples.h instead of
// scanning each triangle. Checked here against the tie rule written out independently: each
// sample's owner found by testing it against every triangle, its weights the exact ratio of
// the triangle's edge functions.
#include <catch2/catch.hpp>

#include <random>

#include "mesh.h"
#include "render.h"
#include "test_support.h"

namespace {

// What a triangle owns at ×3 of a width × height input whose crop (cx, cy) the mesh covers.
struct Owned {
    uint32_t x, y;      // output column and row
    double weights[3];  // for v0, v1, v2
};

// Sample coordinate of output index i of 3·in, clamped into the hull, in units of 1/6 pixel:
// (i + 0.5) / 3 − 0.5 pixels.
int64_t sixths(uint32_t i, uint32_t in) { return std::clamp<int64_t>(2 * int64_t(i) - 2, 0, 6 * (int64_t(in) - 1)); }

// The samples of rows [y_begin, y_end) that triangle t owns under raster.h's tie rule: a
// sample on an edge is pushed by (dir_u·ε, dir_v·ε²), dir = −1 on the hull's last column or
// row and +1 elsewhere. Here ε = 1/K with K = 2^20 beyond every coordinate: all coordinates
// times K², the sample moved by (dir_u·K, dir_v).
std::vector<Owned> ownedSamples(const ddt::Mesh& mesh, const ddt::Triangle& t, uint32_t in_w, uint32_t in_h, uint32_t cx,
                                uint32_t cy, uint32_t y_begin, uint32_t y_end) {
    const __int128 k = __int128(1) << 20;
    const uint32_t ids[3] = {t.v0, t.v1, t.v2};
    int64_t vx[3], vy[3];  // sixths
    for (int i = 0; i < 3; ++i) {
        vx[i] = 6 * int64_t(ids[i] % mesh.width + cx);
        vy[i] = 6 * int64_t(ids[i] / mesh.width + cy);
    }
    std::vector<Owned> owned;
    for (uint32_t y = y_begin; y < y_end; ++y)
        for (uint32_t x = 0; x < 3 * in_w; ++x) {
            const int64_t u = sixths(x, in_w), v = sixths(y, in_h);
            const int dir_u = u == 6 * (int64_t(in_w) - 1) ? -1 : 1, dir_v = v == 6 * (int64_t(in_h) - 1) ? -1 : 1;
            const __int128 su = u * k * k + dir_u * k, sv = v * k * k + dir_v;
            bool inside = true;
            int64_t edge[3];  // the unpushed edge function opposite each vertex
            for (int i = 0; i < 3; ++i) {
                const int p = (i + 1) % 3, q = (i + 2) % 3;
                const __int128 pushed = (__int128(vx[q] - vx[p]) * k * k) * (sv - vy[p] * k * k) -
                                        (__int128(vy[q] - vy[p]) * k * k) * (su - vx[p] * k * k);
                inside = inside && pushed > 0;
                edge[i] = (vx[q] - vx[p]) * (v - vy[p]) - (vy[q] - vy[p]) * (u - vx[p]);
            }
            if (!inside) continue;
            const double total = double(edge[0] + edge[1] + edge[2]);
            owned.push_back({x, y, {edge[0] / total, edge[1] / total, edge[2] / total}});
        }
    return owned;
}

}  // namespace

TEST_CASE("lattice samples: at x3 each triangle of a grid mesh holds the samples of the tie rule, with their exact weights") {
    std::mt19937 rng(7);
    for (auto [w, h] : {std::pair{2u, 2u}, {5u, 3u}, {3u, 7u}, {13u, 9u}, {16u, 16u}}) {
        for (bool flipped : {false, true}) {
            const ddt::Mesh mesh = flipped ? ddt::test::scrambledGridMesh(w, h, rng) : ddt::buildGridMesh(w, h);
            const ddt::Image image = ddt::test::randomImage(rng, w, h, 1);
            const ddt::MeshRenderer renderer(mesh, image);
            const uint32_t triangles = uint32_t(renderer.triangles().size());
            std::vector<ddt::SampleHit> hits;
            std::vector<uint32_t> ends(triangles);
            renderer.locateSamples({3 * w, 3 * h}, 0, triangles, hits, ends.data());
            INFO(w << "x" << h << (flipped ? " flipped" : " grid"));
            REQUIRE(hits.size() == size_t(9) * w * h);
            uint32_t begin = 0;
            size_t mismatches = 0;
            for (uint32_t t = 0; t < triangles; ++t) {
                const std::vector<Owned> expected = ownedSamples(mesh, renderer.triangles()[t], w, h, 0, 0, 0, 3 * h);
                if (ends[t] - begin != expected.size()) {
                    ++mismatches;
                } else {
                    for (size_t n = 0; n < expected.size(); ++n) {
                        const ddt::SampleHit& hit = hits[begin + n];
                        const Owned& e = expected[n];
                        mismatches += hit.sample != e.y * 3 * w + e.x || hit.weights[0] != float(e.weights[0]) ||
                                      hit.weights[1] != float(e.weights[1]) || hit.weights[2] != float(e.weights[2]);
                    }
                }
                begin = ends[t];
            }
            CHECK(mismatches == 0);
        }
    }
}

TEST_CASE("lattice samples: a tile's mesh renders a band at x3 with the tie rule's owners and exact weights") {
    // The tile's crop lies inside a larger input, so its hull lines are not the input's; the
    // band cuts through triangles.
    std::mt19937 rng(11);
    const uint32_t in_w = 20, in_h = 15, cx = 6, cy = 4, w = 9, h = 8;
    const ddt::Mesh mesh = ddt::test::scrambledGridMesh(w, h, rng);
    const ddt::Image crop = ddt::test::randomImage(rng, w, h, 1);
    ddt::RenderWindow window;
    window.input_width = in_w;
    window.input_height = in_h;
    window.out = {3 * in_w, 3 * in_h};
    window.crop_x = cx;
    window.crop_y = cy;
    window.x_begin = 3 * cx + 1;  // from the samples on the crop's first column
    window.x_end = 3 * (cx + w - 1) + 1;  // the last line is the next tile's
    window.y_begin = 3 * cy + 5;
    window.y_end = 3 * (cy + h - 1) - 1;
    std::vector<float> rows(size_t(window.width()) * window.height(), -1.0f);
    ddt::MeshRenderer(mesh, crop).renderWindow(window, rows.data());
    std::vector<float> expected(rows.size(), -1.0f);
    std::vector<int> owners(rows.size(), 0);
    for (const ddt::Triangle& t : ddt::listTriangles(mesh))
        for (const Owned& o : ownedSamples(mesh, t, in_w, in_h, cx, cy, window.y_begin, window.y_end)) {
            if (o.x < window.x_begin || o.x >= window.x_end) continue;
            const size_t i = size_t(o.y - window.y_begin) * window.width() + (o.x - window.x_begin);
            ++owners[i];
            // The plain surface, summed as render.cpp sums it.
            expected[i] = float(o.weights[0] * crop.pixels[t.v0] + o.weights[1] * crop.pixels[t.v1] +
                                o.weights[2] * crop.pixels[t.v2]);
        }
    CHECK(std::all_of(owners.begin(), owners.end(), [](int n) { return n == 1; }));
    CHECK(ddt::test::samePixels(rows, expected));
}
