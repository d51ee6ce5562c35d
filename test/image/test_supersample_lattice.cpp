// The reconstruction's element-wise supersamples (supersample_lattice.h), checked against the
// quadratic surface worked out here in double precision: every supersample located by testing
// it against every triangle, its barycentric weights from the edge functions. The projection
// is checked as the exact transpose of the evaluation.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include "mesh.h"
#include "pixel_vector.h"
#include "supersample_lattice.h"
#include "test_support.h"

namespace {

using ddt::Mesh;
using ddt::SupersampleLattice;
using ddt::Triangle;

// Supersample i of 3·size at (i + 0.5) / 3 − 0.5 pixels, clamped into [0, size − 1], in thirds.
int64_t thirds(uint32_t i, uint32_t size) { return std::clamp<int64_t>(int64_t(i) - 1, 0, 3 * (int64_t(size) - 1)); }

// The surface at every supersample, channel-major within a sample (c values each).
std::vector<double> surfaceAtSupersamples(const Mesh& mesh, const std::vector<Triangle>& triangles,
                                          const std::vector<float>& values, const std::vector<float>& bubbles, uint32_t c) {
    const uint32_t w = mesh.width, h = mesh.height;
    std::vector<double> sub;
    for (uint32_t j = 0; j < 3 * h; ++j)
        for (uint32_t i = 0; i < 3 * w; ++i) {
            const int64_t u = thirds(i, w), v = thirds(j, h);
            bool found = false;
            for (const Triangle& t : triangles) {
                const uint32_t ids[3] = {t.v0, t.v1, t.v2}, edges[3] = {t.e0, t.e1, t.e2};
                int64_t lambda[3];  // edge functions opposite each vertex, in thirds²
                for (int k = 0; k < 3; ++k) {
                    const uint32_t p = ids[(k + 1) % 3], q = ids[(k + 2) % 3];
                    const int64_t px = 3 * (p % w), py = 3 * (p / w), qx = 3 * (q % w), qy = 3 * (q / w);
                    lambda[k] = (qx - px) * (v - py) - (qy - py) * (u - px);
                }
                if (lambda[0] < 0 || lambda[1] < 0 || lambda[2] < 0) continue;
                const double total = double(lambda[0] + lambda[1] + lambda[2]);
                const double l[3] = {lambda[0] / total, lambda[1] / total, lambda[2] / total};
                for (uint32_t k = 0; k < c; ++k) {
                    double s = 0.0;
                    for (int n = 0; n < 3; ++n) s += l[n] * values[ids[n] * c + k];
                    // Edge n is opposite vertex n: its bubble is 4 · the other two weights.
                    for (int n = 0; n < 3; ++n) s += 4.0 * l[(n + 1) % 3] * l[(n + 2) % 3] * bubbles[edges[n] * c + k];
                    sub.push_back(s);
                }
                found = true;
                break;
            }
            REQUIRE(found);
        }
    return sub;
}

// A projection's consumer that keeps each sum, C floats per element.
template <uint32_t C>
auto sumsInto(std::vector<float>& sums) {
    return [&sums](size_t i, ddt::PixelVector<C> sum) { ddt::storePixel<C>(sums.data() + i * C, sum); };
}

std::vector<float> randomValues(size_t count, std::mt19937& rng) {
    std::uniform_real_distribution<float> value(-1.0f, 1.0f);
    std::vector<float> values(count);
    for (float& v : values) v = value(rng);
    return values;
}

// A scrambled w × h grid's lattice, random vertex values and bubbles (c channels), and the
// lattice's surface at its supersamples.
struct RandomSurface {
    Mesh mesh;
    std::vector<Triangle> triangles;
    SupersampleLattice lattice;
    std::vector<float> values, bubbles, sub;

    RandomSurface(uint32_t w, uint32_t h, uint32_t c, std::mt19937& rng)
        : mesh(ddt::test::scrambledGridMesh(w, h, rng)), triangles(ddt::listTriangles(mesh)),
          lattice(w, h, c, mesh.vertices, triangles), values(randomValues(size_t(w) * h * c, rng)),
          bubbles(randomValues(size_t(mesh.edgeCount()) * c, rng)), sub(size_t(9) * w * h * c) {
        lattice.evaluate(values.data(), bubbles.data(), c, sub.data());
    }
};

}  // namespace

TEST_CASE("supersample lattice: the surface at every supersample of a scrambled grid", "[reconstruct]") {
    std::mt19937 rng(71);
    for (auto [w, h] : {std::pair{2u, 2u}, std::pair{13u, 9u}, std::pair{7u, 16u}})
        for (uint32_t c : {1u, 3u}) {
            const RandomSurface s(w, h, c, rng);
            const std::vector<double> expected = surfaceAtSupersamples(s.mesh, s.triangles, s.values, s.bubbles, c);
            double worst = 0.0;
            for (size_t i = 0; i < s.sub.size(); ++i) worst = std::max(worst, std::abs(s.sub[i] - expected[i]));
            // Float rounding of at most seven products and sums of values in [−1, 1].
            CHECK(worst < 1e-5);
        }
}

TEST_CASE("supersample lattice: the projection is the evaluation's transpose", "[reconstruct]") {
    // ⟨evaluate(u), g⟩ = ⟨u, project(g)⟩ for random unknowns u (vertex values and bubbles) and
    // supersamples g, the sums in double.
    std::mt19937 rng(72);
    for (auto [w, h] : {std::pair{2u, 3u}, std::pair{11u, 8u}})
        for (uint32_t c : {1u, 3u}) {
            const RandomSurface s(w, h, c, rng);
            const std::vector<float> g = randomValues(s.sub.size(), rng);
            std::vector<float> projected = g, vertex_sums(s.values.size()), edge_sums(s.bubbles.size());
            if (c == 1)
                s.lattice.project<1>(projected.data(), sumsInto<1>(vertex_sums), sumsInto<1>(edge_sums));
            else
                s.lattice.project<3>(projected.data(), sumsInto<3>(vertex_sums), sumsInto<3>(edge_sums));
            double left = 0.0, right = 0.0, scale = 0.0;
            for (size_t i = 0; i < g.size(); ++i) {
                left += double(s.sub[i]) * g[i];
                scale += std::abs(double(s.sub[i]) * g[i]);
            }
            for (size_t i = 0; i < s.values.size(); ++i) right += double(s.values[i]) * vertex_sums[i];
            for (size_t i = 0; i < s.bubbles.size(); ++i) right += double(s.bubbles[i]) * edge_sums[i];
            // Both sides are float sums of up to ~2000 terms: within 1e-5 of the terms' total size.
            CHECK(std::abs(left - right) < 1e-5 * scale);
        }
}
