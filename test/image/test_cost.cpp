#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

#include "cost.h"
#include "lawson.h"
#include "mesh.h"
#include "test_support.h"

using ddt::kNone;
using ddt::test::edgeBetween;
using ddt::test::greyImage;
using ddt::test::makeImage;

namespace {

const double kMinusInfinity = -std::numeric_limits<double>::infinity();

// The 2×2 grid: vertices 0 (0,0), 1 (1,0), 2 (0,1), 3 (1,1); edge 2 is the only interior one.
//
//     0 --0-- 1
//     | `.    |        left triangle of 0–3: (0, 3, 2)
//     1   2   3        right triangle:       (3, 0, 1)
//     |    `. |
//     2 --4-- 3
const uint32_t kDiagonal = 2;

ddt::CostField fieldOf(const ddt::Image& image) { return ddt::costFieldOf(image); }

// A plane z = c + a·x + b·y sampled on a width × height grey image.
ddt::Image planeImage(uint32_t width, uint32_t height, double a, double b, double c) {
    std::vector<float> pixels;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) pixels.push_back(float(c + a * x + b * y));
    return makeImage(width, height, 1, pixels);
}

bool isHullEdge(const ddt::Mesh& mesh, uint32_t e) {
    return mesh.vertices[e].l == kNone || mesh.vertices[e].r == kNone;
}

}  // namespace

TEST_CASE("cost: luma uses the Rec. 601 weights, alpha is kept apart") {
    ddt::Image rgba = makeImage(2, 1, 4, {1.0f, 0.0f, 0.0f, 1.0f, 0.2f, 0.4f, 0.6f, 0.5f});
    ddt::CostField field = fieldOf(rgba);
    REQUIRE(field.luma.size() == 2);
    REQUIRE(field.alpha.size() == 2);
    CHECK(field.luma[0] == Approx(0.299).margin(1e-7));  // float storage: 2^-24 relative
    CHECK(field.luma[1] == Approx(0.299 * 0.2 + 0.587 * 0.4 + 0.114 * 0.6).margin(1e-7));  // 0.4176
    CHECK(field.alpha[0] == 1.0f);
    CHECK(field.alpha[1] == 0.5f);
    ddt::CostField grey = fieldOf(makeImage(2, 1, 1, {0.25f, 0.75f}));
    CHECK(grey.luma == std::vector<float>{0.25f, 0.75f});
    CHECK(grey.alpha.empty());
}

TEST_CASE("cost: a bright corner on the diagonal costs 1 and its flip gains 1") {
    // z = 1 0      left (0,3,2): z = 1 − y, gradient (0, −1)
    //     0 0      right (3,0,1): z = 1 − x, gradient (−1, 0)
    // SCF = |(0,−1)|·|(−1,0)| − (0,−1)·(−1,0) = 1 − 0 = 1.
    // Flipped to 1–2: (1,3,2) is flat 0, (2,0,1) is z = 1 − x − y; a flat plane costs 0.
    ddt::Image image = greyImage({{1, 0}, {0, 0}});
    ddt::Mesh mesh = ddt::buildGridMesh(2, 2);
    ddt::CostField field = fieldOf(image);
    CHECK(ddt::edgeCost(mesh, field, kDiagonal) == 1.0);
    CHECK(ddt::meshCost(mesh, field) == 1.0);
    CHECK(ddt::flipGainOf(mesh, field, kDiagonal) == 1.0);
    ddt::flipEdge(mesh, kDiagonal);
    CHECK(ddt::meshCost(mesh, field) == 0.0);
    CHECK(ddt::flipGainOf(mesh, field, kDiagonal) == -1.0);
}

TEST_CASE("cost: a bright corner off the diagonal costs 0 and its flip would cost 1") {
    // z = 0 1      left (0,3,2) flat 0: SCF 0 whatever the right triangle.
    //     0 0      Flipped to 1–2: (1,3,2) z = 1 − y, gradient (0, −1); (2,0,1) z = x,
    //              gradient (1, 0); SCF = 1·1 − 0 = 1, so the gain is 0 − 1 = −1.
    ddt::Image image = greyImage({{0, 1}, {0, 0}});
    ddt::Mesh mesh = ddt::buildGridMesh(2, 2);
    ddt::CostField field = fieldOf(image);
    CHECK(ddt::edgeCost(mesh, field, kDiagonal) == 0.0);
    CHECK(ddt::flipGainOf(mesh, field, kDiagonal) == -1.0);
    ddt::OptimizeStats stats = ddt::optimizeSerial(mesh, field);
    CHECK(stats.flips == 0);
    CHECK(mesh.vertices[kDiagonal].a == 0);
    CHECK(mesh.vertices[kDiagonal].b == 3);
}

TEST_CASE("cost: SCF of a 2x2 cell with four different values, by hand") {
    // z = 0.5  1        left (0,3,2): c = 0.5; z(0,1) = 0 -> b = −0.5; z(1,1) = 0.25 -> a = 0.25
    //     0    0.25     right (3,0,1): c = 0.5; z(1,0) = 1 -> a = 0.5; z(1,1) = 0.25 -> b = −0.75
    // |gL|² = 0.3125 = 5/16, |gR|² = 0.8125 = 13/16, gL·gR = 0.125 + 0.375 = 0.5
    // SCF = sqrt(65)/16 − 1/2 ≈ 0.0038911
    // Flipped to 1–2: (1,3,2) gradient (0.25, −0.75), (2,0,1) gradient (0.5, −0.5):
    // SCF = sqrt(10/16)·sqrt(1/2) − 0.5 = sqrt(5)/4 − 1/2 ≈ 0.0590170, so the gain is
    // sqrt(65)/16 − sqrt(5)/4 ≈ −0.0551259 (no flip).
    ddt::Image image = greyImage({{0.5f, 1.0f}, {0.0f, 0.25f}});
    ddt::Mesh mesh = ddt::buildGridMesh(2, 2);
    ddt::CostField field = fieldOf(image);
    // The values and gradients are exact in binary; only the square roots and the final
    // subtraction round (a few ulps of 0.5).
    CHECK(ddt::edgeCost(mesh, field, kDiagonal) == Approx(std::sqrt(65.0) / 16 - 0.5).margin(1e-15));
    CHECK(ddt::flipGainOf(mesh, field, kDiagonal) == Approx(std::sqrt(65.0) / 16 - std::sqrt(5.0) / 4).margin(1e-15));
    ddt::flipEdge(mesh, kDiagonal);
    CHECK(ddt::edgeCost(mesh, field, kDiagonal) == Approx(std::sqrt(5.0) / 4 - 0.5).margin(1e-15));
}

TEST_CASE("cost: a plane costs exactly 0 on every edge and needs no flip") {
    // z = 1/8 + 3x/128 + 4y/128: every value is a float, every grid triangle has twice-area ±1,
    // so each gradient is exactly (3, 4)/128, whose norm 5/128 is exact: norms − dot = 0 exactly.
    // Flipped quads of the grid are unit parallelograms, so every gain is exactly 0 too.
    for (auto [a, b] : {std::pair{3.0, 4.0}, {-4.0, 3.0}, {0.0, 5.0}}) {
        ddt::Image image = planeImage(9, 7, a / 128, b / 128, 0.5);
        ddt::Mesh mesh = ddt::buildGridMesh(9, 7);
        ddt::CostField field = fieldOf(image);
        INFO("gradient (" << a << ", " << b << ")/128");
        for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
            CHECK(ddt::edgeCost(mesh, field, e) == 0.0);
            if (!isHullEdge(mesh, e)) CHECK(ddt::flipGainOf(mesh, field, e) == 0.0);
        }
        ddt::OptimizeStats stats = ddt::optimizeSerial(mesh, field);
        CHECK(stats.flips == 0);
        CHECK(stats.iterations == 1);
        CHECK(stats.cost_final == 0.0);
    }
}

TEST_CASE("cost: any linear image costs 0 on any triangulation, up to rounding") {
    // Random planes, grey and RGB (luma of linear channels is linear), on randomly flipped
    // meshes. The values are rounded to float (2^-24 relative), so two gradients of the same
    // plane differ in direction by θ ≲ 1e-6 rad and SCF = |g1||g2|(1 − cos θ) ≈ |g|²θ²/2;
    // with |g| ≲ 1 that is far below 1e-10.
    std::mt19937 rng(31337);
    std::uniform_real_distribution<double> slope(-0.05, 0.05);
    for (int round = 0; round < 10; ++round) {
        const uint32_t w = 6 + round, h = 4 + round / 2;
        const double a = slope(rng), b = slope(rng);
        std::vector<float> pixels;
        const uint32_t channels = round % 2 ? 3 : 1;
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x)
                for (uint32_t k = 0; k < channels; ++k) pixels.push_back(float(0.5 + (k + 1) * (a * x + b * y)));
        ddt::Image image = makeImage(w, h, channels, pixels);
        ddt::Mesh mesh = ddt::buildGridMesh(w, h);
        ddt::test::flipRandomEdges(mesh, rng, w * h);
        ddt::CostField field = fieldOf(image);
        for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
            INFO("round " << round << " edge " << e);
            CHECK(std::abs(ddt::edgeCost(mesh, field, e)) < 1e-10);
            const double gain = ddt::flipGainOf(mesh, field, e);
            if (gain != kMinusInfinity) CHECK(std::abs(gain) < 1e-10);
        }
    }
}

TEST_CASE("cost: flipGainOf equals the drop of meshCost when the edge is flipped") {
    // Random images (grey, RGB, RGBA) on randomly flipped meshes. meshCost adds ~100 edge costs
    // in id order, each rounding by 2^-53 relative to the running sum; the flip changes five
    // of them, so the two totals differ from the exact drop by ≲ 100 · 2^-53 · total ≈ 1e-14 ·
    // total. Tolerance 1e-12 · (1 + total). The other edges' costs must not change at all.
    std::mt19937 rng(4242);
    size_t tested = 0;
    for (uint32_t channels : {1u, 3u, 4u}) {
        for (int round = 0; round < 6; ++round) {
            ddt::Image image = ddt::test::randomImage(rng, 7, 6, channels, round % 2 ? 3 : 0);
            ddt::Mesh mesh = ddt::buildGridMesh(7, 6);
            ddt::test::flipRandomEdges(mesh, rng, 30);
            ddt::CostField field = fieldOf(image);
            const double total = ddt::meshCost(mesh, field);
            for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
                const double gain = ddt::flipGainOf(mesh, field, e);
                if (gain == kMinusInfinity) continue;
                INFO("channels " << channels << " round " << round << " edge " << e);
                ddt::Mesh flipped = mesh;
                ddt::flipEdge(flipped, e);
                CHECK(gain == Approx(total - ddt::meshCost(flipped, field)).margin(1e-12 * (1 + total)));
                std::vector<uint32_t> changed = ddt::regionOf(mesh, e, 1);
                changed.push_back(e);
                for (uint32_t f = 0; f < mesh.edgeCount(); ++f) {
                    if (std::find(changed.begin(), changed.end(), f) != changed.end()) continue;
                    CHECK(ddt::edgeCost(flipped, field, f) == ddt::edgeCost(mesh, field, f));
                }
                ++tested;
            }
        }
    }
    CHECK(tested > 300);
}

TEST_CASE("cost: the gain of flipping back is the negative") {
    // Both gains add the same five edge costs (bit-identical: planeGradient canonicalises the
    // triangle) in a different order, so they differ by a few ulps of the sum of the costs.
    std::mt19937 rng(77);
    for (int round = 0; round < 12; ++round) {
        ddt::Image image = ddt::test::randomImage(rng, 6, 6, round % 3 == 2 ? 4 : 1, round % 2 ? 4 : 0);
        ddt::Mesh mesh = ddt::buildGridMesh(6, 6);
        ddt::test::flipRandomEdges(mesh, rng, 20);
        ddt::CostField field = fieldOf(image);
        for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
            const double gain = ddt::flipGainOf(mesh, field, e);
            if (gain == kMinusInfinity) continue;
            double scale = ddt::edgeCost(mesh, field, e);
            for (uint32_t f : ddt::regionOf(mesh, e, 1)) scale += ddt::edgeCost(mesh, field, f);
            ddt::flipEdge(mesh, e);
            INFO("round " << round << " edge " << e);
            CHECK(ddt::flipGainOf(mesh, field, e) == Approx(-gain).margin(1e-14 * (1 + 2 * scale)));
            ddt::flipEdge(mesh, e);
        }
    }
}

TEST_CASE("cost: a non-convex quadrilateral gives -infinity") {
    // 4×3 grid. Flip 1–5 (to 0–6), then 4–5 (to 0–9); the diagonal e = 0–5 now lies between
    // (0, 5, 9) and (5, 0, 6), and its quadrilateral 0, 6, 5, 9 is a dart, reflex at 5: the
    // other diagonal 6–9 passes outside it.
    //
    //     0 o
    //        \`-.__
    //         \ `.  `--.__
    //          \  `.  e   `--.__
    //           \   `o----------o 6
    //            \   |5       .'
    //             \  |     .'
    //              \ |  .'
    //               `o'9
    ddt::Mesh mesh = ddt::buildGridMesh(4, 3);
    for (auto [p, q] : {std::pair{1u, 5u}, {4u, 5u}}) {
        const uint32_t f = edgeBetween(mesh, p, q);
        REQUIRE(ddt::flipIsConvex(ddt::flipStencil(mesh, f), ddt::placesOf(mesh)));
        ddt::flipEdge(mesh, f);
    }
    REQUIRE(ddt::checkMesh(mesh) == "");
    const uint32_t e = edgeBetween(mesh, 0, 5);
    REQUIRE(e == 2);
    CHECK(mesh.vertices[e].l == 9);
    CHECK(mesh.vertices[e].r == 6);
    CHECK_FALSE(ddt::flipIsConvex(ddt::flipStencil(mesh, e), ddt::placesOf(mesh)));
    std::mt19937 rng(3);
    for (int round = 0; round < 5; ++round) {
        ddt::CostField field = fieldOf(ddt::test::randomImage(rng, 4, 3, 1));
        CHECK(ddt::flipGainOf(mesh, field, e) == kMinusInfinity);
    }

    // Also a degenerate one: on the 3×3 grid after flipping 0–4 to 1–3, the edge 1–4 has the
    // quad 1, 5, 4, 3 with 3, 4, 5 on one line.
    ddt::Mesh grid = ddt::buildGridMesh(3, 3);
    ddt::flipEdge(grid, 2);
    const uint32_t f = edgeBetween(grid, 1, 4);
    CHECK(grid.vertices[f].l == 3);
    CHECK(grid.vertices[f].r == 5);
    CHECK(ddt::flipGainOf(grid, fieldOf(ddt::test::randomImage(rng, 3, 3, 1)), f) == kMinusInfinity);
}

TEST_CASE("cost: -infinity exactly when the quadrilateral is not strictly convex") {
    std::mt19937 rng(11);
    ddt::Image image = ddt::test::randomImage(rng, 9, 8, 3);
    ddt::CostField field = fieldOf(image);
    ddt::Mesh mesh = ddt::buildGridMesh(9, 8);
    size_t minus_infinity = 0;
    for (int round = 0; round < 10; ++round) {
        ddt::test::flipRandomEdges(mesh, rng, 20);
        for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
            const double gain = ddt::flipGainOf(mesh, field, e);
            INFO("edge " << e);
            CHECK((gain == kMinusInfinity) == !ddt::test::quadIsStrictlyConvex(mesh, e));
            CHECK(!std::isnan(gain));
            minus_infinity += gain == kMinusInfinity && !isHullEdge(mesh, e);
        }
    }
    CHECK(minus_infinity > 0);  // interior non-convex quads did occur
}

TEST_CASE("cost: hull edges cost 0 and are never flippable") {
    std::mt19937 rng(12);
    for (uint32_t channels : {1u, 2u, 3u, 4u}) {
        ddt::Image image = ddt::test::randomImage(rng, 7, 5, channels);
        ddt::Mesh mesh = ddt::buildGridMesh(7, 5);
        ddt::test::flipRandomEdges(mesh, rng, 25);
        ddt::CostField field = fieldOf(image);
        size_t hull = 0;
        for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
            if (!isHullEdge(mesh, e)) continue;
            CHECK(ddt::edgeCost(mesh, field, e) == 0.0);
            CHECK(ddt::flipGainOf(mesh, field, e) == kMinusInfinity);
            ++hull;
        }
        CHECK(hull == 2 * (6 + 4));  // the hull of a 7×5 grid has 2·(6 + 4) unit edges
    }
}

TEST_CASE("cost: alpha edges count even when the colour is flat") {
    // Premultiplied black stays 0 under any alpha, so luma is flat; alpha is the bright-corner
    // case above: cost 1, gain 1.
    ddt::Image rgba = makeImage(2, 2, 4, {0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
    ddt::Image grey_alpha = makeImage(2, 2, 2, {0, 1, 0, 0, 0, 0, 0, 0});
    for (const ddt::Image* image : {&rgba, &grey_alpha}) {
        ddt::Mesh mesh = ddt::buildGridMesh(2, 2);
        ddt::CostField field = fieldOf(*image);
        INFO(image->channels << " channels");
        CHECK(ddt::edgeCost(mesh, field, kDiagonal) == 1.0);
        CHECK(ddt::flipGainOf(mesh, field, kDiagonal) == 1.0);
        ddt::OptimizeStats stats = ddt::optimizeSerial(mesh, field);
        CHECK(stats.flips == 1);
        CHECK(stats.cost_final == 0.0);
    }

    // Opaque alpha adds nothing: RGBA with alpha 1 costs exactly what its RGB does.
    std::mt19937 rng(13);
    ddt::Image rgb = ddt::test::randomImage(rng, 6, 5, 3);
    std::vector<float> pixels;
    for (size_t i = 0; i < rgb.pixels.size(); i += 3) pixels.insert(pixels.end(), {rgb.pixels[i], rgb.pixels[i + 1], rgb.pixels[i + 2], 1.0f});
    ddt::Image opaque = makeImage(6, 5, 4, pixels);
    ddt::Mesh mesh = ddt::buildGridMesh(6, 5);
    ddt::test::flipRandomEdges(mesh, rng, 20);
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
        CHECK(ddt::edgeCost(mesh, fieldOf(opaque), e) == ddt::edgeCost(mesh, fieldOf(rgb), e));
        CHECK(ddt::flipGainOf(mesh, fieldOf(opaque), e) == ddt::flipGainOf(mesh, fieldOf(rgb), e));
    }
}
