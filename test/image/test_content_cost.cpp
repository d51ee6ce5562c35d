// Tóth et al.'s content-weighted costs (glsl/image/content_cost.h): Σ over triangles of area × weight,
// the weight the variance of the triangle's three values or the mean over its three edges of
// Sederberg's cost (face-SCF). Hand-computed costs and gains, the serial optimizer with each
// cost, and the Vulkan backend against it on lavapipe (with the validation layer, zero
// messages required).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "backend.h"
#include "cost.h"
#include "flip_rule.h"
#include "image_file.h"
#include "lawson.h"
#include "mesh.h"
#include "test_support.h"
#include "vulkan_backend.h"

namespace {

using namespace ddt;
using test::edgeBetween;
using test::greyImage;
using test::makeImage;

const double kMinusInfinity = -std::numeric_limits<double>::infinity();
const CostFunction kContentCosts[] = {CostFunction::variance, CostFunction::face_scf};
const CostFunction kAllCosts[] = {CostFunction::sederberg, CostFunction::variance, CostFunction::face_scf};

// The 3×2 image of the face-SCF and variance examples below, its grid triangulation and the
// gradients of its four triangles (y grows downwards; ∇ = (∂z/∂x, ∂z/∂y)):
//
//   (0,0)=0 ---- (1,0)=0 ---- (2,0)=1        T1 = (0,0) (1,1) (0,1): values 0 1 0, ∇ (1, 0)
//      |  `.  T2   |  `.  T4   |             T2 = (1,1) (0,0) (1,0): values 1 0 0, ∇ (0, 1)
//      | T1  `.    | T3  `.    |             T3 = (1,0) (2,1) (1,1): values 0 0 1, ∇ (−1, 1)
//   (0,1)=0 ---- (1,1)=1 ---- (2,1)=0        T4 = (2,1) (1,0) (2,0): values 0 0 1, ∇ (1, −1)
//
// SCF of the interior edges: diagonal (0,0)–(1,1) between T1, T2: 1·1 − 0 = 1; vertical
// (1,0)–(1,1) between T2, T3: 1·√2 − 1 = √2 − 1; diagonal (1,0)–(2,1) between T3, T4:
// √2·√2 − (−2) = 4. Every triangle has area 1/2.
Image threeByTwo() { return greyImage({{0, 0, 1}, {0, 1, 0}}); }

// Independent evaluation of Σ area(T) · w(T) straight from the paper's definition: plane
// gradients by Cramer's rule, the variance about the mean, the SCF as |g1||g2| − g1·g2, the
// weight of face-SCF the mean over T's three edges (a hull edge 0). Channels: luma, then
// alpha if any, added.
double triangleFormCost(const Mesh& mesh, const CostField& field, CostFunction cost) {
    const std::vector<Triangle> triangles = listTriangles(mesh);
    std::vector<std::vector<size_t>> of_edge(mesh.edgeCount());
    for (size_t t = 0; t < triangles.size(); ++t)
        for (uint32_t e : {triangles[t].e0, triangles[t].e1, triangles[t].e2}) of_edge[e].push_back(t);
    double total = 0.0;
    for (const std::vector<float>* z : {&field.luma, &field.alpha}) {
        if (z->empty()) continue;
        std::vector<std::array<double, 2>> gradient(triangles.size());
        for (size_t t = 0; t < triangles.size(); ++t) {
            const Triangle& tr = triangles[t];
            const double x0 = tr.v0 % mesh.width, y0 = tr.v0 / mesh.width;
            const double ax = double(tr.v1 % mesh.width) - x0, ay = double(tr.v1 / mesh.width) - y0;
            const double bx = double(tr.v2 % mesh.width) - x0, by = double(tr.v2 / mesh.width) - y0;
            const double dz1 = double((*z)[tr.v1]) - (*z)[tr.v0], dz2 = double((*z)[tr.v2]) - (*z)[tr.v0];
            const double det = ax * by - ay * bx;
            gradient[t] = {(dz1 * by - dz2 * ay) / det, (ax * dz2 - bx * dz1) / det};
        }
        for (size_t t = 0; t < triangles.size(); ++t) {
            const Triangle& tr = triangles[t];
            const double area = 0.5 * double(test::twiceArea(mesh, tr.v0, tr.v1, tr.v2));
            double weight = 0.0;
            if (cost == CostFunction::variance) {
                const double z0 = (*z)[tr.v0], z1 = (*z)[tr.v1], z2 = (*z)[tr.v2];
                const double mean = (z0 + z1 + z2) / 3.0;
                weight = ((z0 - mean) * (z0 - mean) + (z1 - mean) * (z1 - mean) + (z2 - mean) * (z2 - mean)) / 3.0;
            } else {
                for (uint32_t e : {tr.e0, tr.e1, tr.e2}) {
                    if (of_edge[e].size() < 2) continue;
                    const auto& g1 = gradient[of_edge[e][0]];
                    const auto& g2 = gradient[of_edge[e][1]];
                    weight += std::hypot(g1[0], g1[1]) * std::hypot(g2[0], g2[1]) - (g1[0] * g2[0] + g1[1] * g2[1]);
                }
                weight /= 3.0;
            }
            total += area * weight;
        }
    }
    return total;
}

// Runs optimizeSerial with `cost`, checking the cost after every sweep never rises.
OptimizeStats optimizeWatched(Mesh& mesh, const CostField& field, CostFunction cost, bool& monotone) {
    LawsonOptions options;
    options.cost = cost;
    double previous = meshCost(mesh, field, cost);
    monotone = true;
    options.after_sweep = [&](uint32_t, const Mesh& now) {
        const double now_cost = meshCost(now, field, cost);
        // Every flip lowers the exact cost by more than the threshold; meshCost rounds by
        // ≲ edges · 2^-53 relative.
        monotone = monotone && now_cost <= previous + 1e-12 * (1.0 + std::abs(previous));
        previous = now_cost;
    };
    return optimizeSerial(mesh, field, options);
}

// The largest gain left anywhere, by brute force over every edge.
double largestGain(const Mesh& mesh, const CostField& field, CostFunction cost) {
    double largest = kMinusInfinity;
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) largest = std::max(largest, flipGainOf(mesh, field, e, cost));
    return largest;
}

struct TestImage {
    std::string label;
    Image image;
};

std::vector<TestImage> testImages() {
    std::mt19937 rng(2024);
    std::vector<TestImage> images;
    images.push_back({"random grey 17x13", test::randomImage(rng, 17, 13, 1)});
    images.push_back({"four-level grey 20x20", test::randomImage(rng, 20, 20, 1, 4)});
    images.push_back({"random RGB 13x9", test::randomImage(rng, 13, 9, 3)});
    images.push_back({"random RGBA 11x14", test::randomImage(rng, 11, 14, 4)});
    images.push_back({"astronaut crop 32x32", readImage(test::testDataPath("crop32_astronaut.png"))});
    return images;
}

}  // namespace

TEST_CASE("content cost: names parse back, and each cost has its ROI", "[content-cost]") {
    for (CostFunction cost : kAllCosts) CHECK(parseCostFunction(costFunctionName(cost)) == cost);
    CHECK(std::string(costFunctionName(CostFunction::face_scf)) == "face-scf");
    CHECK_FALSE(parseCostFunction("face_scf"));
    CHECK_FALSE(parseCostFunction(""));
    CHECK(roiDegree(CostFunction::sederberg) == 2);
    CHECK(roiDegree(CostFunction::face_scf) == 2);
    CHECK(roiDegree(CostFunction::variance) == 1);
}

TEST_CASE("content cost: area × variance of a 2x2 cell's triangles, and its flip, by hand", "[content-cost]") {
    // z = 0.5  1        diagonal 0–3: left (0,3,2) values 0.5 0.25 0: mean 0.25, variance
    //     0    0.25       (0.0625 + 0 + 0.0625) / 3 = 1/24, × area 1/2 = 1/48;
    //                     right (3,0,1) values 0.25 0.5 1: mean 7/12, deviations −4, −1, 5 (/12),
    //                     variance 42/144 / 3 = 7/72, × 1/2 = 7/144. Total 10/144 = 5/72.
    // Flipped to 1–2: (1,3,2) values 1 0.25 0: mean 5/12, deviations 7, −2, −5 (/12), variance
    // 78/432 = 13/72, × 1/2 = 13/144; (2,0,1) values 0 0.5 1: variance 1/6, × 1/2 = 12/144.
    // Total 25/144: the gain is (10 − 25)/144 = −5/48, no flip.
    const Image image = greyImage({{0.5f, 1.0f}, {0.0f, 0.25f}});
    Mesh mesh = buildGridMesh(2, 2);
    const CostField field = costFieldOf(image);
    const CostFunction variance = CostFunction::variance;
    const uint32_t diagonal = edgeBetween(mesh, 0, 3);
    // The values are exact in binary: only the division by 18 rounds.
    CHECK(meshCost(mesh, field, variance) == Approx(5.0 / 72).margin(1e-16));
    CHECK(triangleFormCost(mesh, field, variance) == Approx(5.0 / 72).margin(1e-16));
    // Each triangle's cost is the share of its lowest-id edge: (3,0,1) of 0–1 (edge 0),
    // (0,3,2) of 0–2 (edge 1); the diagonal (edge 2) reports neither.
    CHECK(edgeCost(mesh, field, edgeBetween(mesh, 0, 1), variance) == Approx(7.0 / 144).margin(1e-16));
    CHECK(edgeCost(mesh, field, edgeBetween(mesh, 0, 2), variance) == Approx(1.0 / 48).margin(1e-16));
    CHECK(edgeCost(mesh, field, diagonal, variance) == 0.0);
    CHECK(flipGainOf(mesh, field, diagonal, variance) == Approx(-5.0 / 48).margin(1e-16));
    flipEdge(mesh, diagonal);
    CHECK(meshCost(mesh, field, variance) == Approx(25.0 / 144).margin(1e-16));
    CHECK(flipGainOf(mesh, field, diagonal, variance) == Approx(5.0 / 48).margin(1e-16));
    // The optimizer flips it back, and reports the costs of both meshes.
    const OptimizeStats stats = optimizeSerial(mesh, field, {.cost = variance});
    CHECK(stats.flips == 1);
    CHECK(stats.cost_init == Approx(25.0 / 144).margin(1e-16));
    CHECK(stats.cost_final == Approx(5.0 / 72).margin(1e-16));
}

TEST_CASE("content cost: alpha adds its own area × variance", "[content-cost]") {
    // Black premultiplied colour (luma 0 everywhere) and alpha 1 at vertex 0 only: on the
    // diagonal 0–3 each triangle has alpha values {1, 0, 0}: variance 2/9, × 1/2 = 1/9 each.
    const Image rgba = makeImage(2, 2, 4, {0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
    const Mesh mesh = buildGridMesh(2, 2);
    const CostField field = costFieldOf(rgba);
    CHECK(meshCost(mesh, field, CostFunction::variance) == Approx(2.0 / 9).margin(1e-16));
    // Flipped to 1–2: (1,3,2) flat 0, (2,0,1) {0, 1, 0}: 1/9. Gain 1/9.
    CHECK(flipGainOf(mesh, field, edgeBetween(mesh, 0, 3), CostFunction::variance) == Approx(1.0 / 9).margin(1e-16));
}

TEST_CASE("content cost: face-SCF of a 3x2 image with known gradients, by hand", "[content-cost]") {
    // threeByTwo(): weights w = (Σ SCF of the triangle's edges) / 3, hull edges 0:
    //   w(T1) = 1/3, w(T2) = (1 + √2 − 1)/3 = √2/3, w(T3) = (√2 − 1 + 4)/3, w(T4) = 4/3;
    //   cost = 1/2 · (1 + √2 + 3 + √2 + 4)/3 = (4 + √2)/3, a third of Sederberg's 4 + √2.
    const Image image = threeByTwo();
    Mesh mesh = buildGridMesh(3, 2);
    const CostField field = costFieldOf(image);
    const CostFunction face = CostFunction::face_scf;
    const double sqrt2 = std::sqrt(2.0);
    CHECK(meshCost(mesh, field, CostFunction::sederberg) == Approx(4 + sqrt2).margin(1e-15));
    CHECK(meshCost(mesh, field, face) == Approx((4 + sqrt2) / 3).margin(1e-15));
    CHECK(triangleFormCost(mesh, field, face) == Approx((4 + sqrt2) / 3).margin(1e-15));
    // Edge shares: SCF · (1/2 + 1/2) / 3.
    const uint32_t diagonal0 = edgeBetween(mesh, 0, 4), vertical = edgeBetween(mesh, 1, 4),
                   diagonal1 = edgeBetween(mesh, 1, 5);
    CHECK(edgeCost(mesh, field, diagonal0, face) == Approx(1.0 / 3).margin(1e-15));
    CHECK(edgeCost(mesh, field, vertical, face) == Approx((sqrt2 - 1) / 3).margin(1e-15));
    CHECK(edgeCost(mesh, field, diagonal1, face) == Approx(4.0 / 3).margin(1e-15));

    // Flipping diagonal 0 to (1,0)–(0,1): V1 = (0,0) (1,0) (0,1) is flat, V2 = (1,0) (1,1) (0,1)
    // has ∇ (1, 1). The new diagonal costs 0 (one plane flat); the vertical edge now lies
    // between V2 and T3: √2·√2 − (−1 + 1) = 2. Weights: V1 0, V2 2/3, T3 (2 + 4)/3, T4 4/3;
    // cost 1/2 · 12/3 = 2. Gain (4 + √2)/3 − 2 = (√2 − 2)/3: the flip would raise face-SCF,
    // and Sederberg's by three times as much.
    CHECK(flipGainOf(mesh, field, diagonal0, face) == Approx((sqrt2 - 2) / 3).margin(1e-15));
    CHECK(flipGainOf(mesh, field, diagonal0, CostFunction::sederberg) == Approx(sqrt2 - 2).margin(1e-15));
    // Flipping diagonal 1 to (2,0)–(1,1): U1 = (1,0) (2,0) (1,1) with ∇ (1, 1), U2 = (2,0) (2,1)
    // (1,1) with ∇ (−1, −1): new diagonal 4, vertical between T2 and U1 √2 − 1, as before: gain 0.
    CHECK(flipGainOf(mesh, field, diagonal1, face) == Approx(0.0).margin(1e-15));
    Mesh flipped = mesh;
    flipEdge(flipped, diagonal0);
    CHECK(meshCost(flipped, field, face) == Approx(2.0).margin(1e-15));
    CHECK(triangleFormCost(flipped, field, face) == Approx(2.0).margin(1e-15));
}

TEST_CASE("content cost: variance and face-SCF flip different edges of one image, by hand", "[content-cost]") {
    // threeByTwo(): every triangle holds one 1 and two 0s: variance 2/9, × 1/2 = 1/9; cost 4/9.
    // - Diagonal 0 (edge 2) to (1,0)–(0,1): V1 = (0,0) (1,0) (0,1), all 0, and V2 = (1,0) (1,1)
    //   (0,1) with one 1: variance gain 1/9 + 1/9 − 0 − 1/9 = 1/9; face-SCF's (√2 − 2)/3 < 0
    //   (the face-SCF example above).
    // - The vertical (1,0)–(1,1) (edge 4), across the parallelogram (0,0) (1,0) (2,1) (1,1), to
    //   (0,0)–(2,1): W1 = (0,0) (1,0) (2,1) flat, W2 = (0,0) (2,1) (1,1) with ∇ (−1, 2). Variance
    //   gain 1/9 + 1/9 − 0 − 1/9 = 1/9. SCF: the edge itself √2 − 1 → 0 (W1 flat), diagonal 1
    //   4 → 0 (W1 flat), diagonal 0 1 → |(1,0)|·|(−1,2)| + 1 = √5 + 1: Sederberg's gain
    //   3 + √2 − √5, face-SCF's a third of it.
    // - Diagonal 1 (edge 5): the variance gain is 0 (U1 values 0 1 1, U2 1 0 1), the SCF gain 0
    //   (the face-SCF example above).
    // Lawson's sweep in id order flips edge 2 under variance (the vertical's quadrilateral then
    // has (1,1) on its side (0,1)–(2,1), not strictly convex) and edge 4 under face-SCF.
    const Image image = threeByTwo();
    const CostField field = costFieldOf(image);
    const CostFunction variance = CostFunction::variance, face = CostFunction::face_scf;
    const double sqrt2 = std::sqrt(2.0), sqrt5 = std::sqrt(5.0);
    Mesh mesh = buildGridMesh(3, 2);
    const uint32_t diagonal0 = edgeBetween(mesh, 0, 4), vertical = edgeBetween(mesh, 1, 4),
                   diagonal1 = edgeBetween(mesh, 1, 5);
    CHECK(meshCost(mesh, field, variance) == Approx(4.0 / 9).margin(1e-16));
    CHECK(flipGainOf(mesh, field, diagonal0, variance) == Approx(1.0 / 9).margin(1e-16));
    CHECK(flipGainOf(mesh, field, vertical, variance) == Approx(1.0 / 9).margin(1e-16));
    CHECK(flipGainOf(mesh, field, diagonal1, variance) == Approx(0.0).margin(1e-16));
    CHECK(flipGainOf(mesh, field, vertical, CostFunction::sederberg) == Approx(3 + sqrt2 - sqrt5).margin(1e-15));
    CHECK(flipGainOf(mesh, field, vertical, face) == Approx((3 + sqrt2 - sqrt5) / 3).margin(1e-15));

    const OptimizeStats by_variance = optimizeSerial(mesh, field, {.cost = variance});
    CHECK(by_variance.flips == 1);
    CHECK(edgeBetween(mesh, 1, 3) != kNone);  // the new diagonal (1,0)–(0,1)
    CHECK(by_variance.cost_final == Approx(3.0 / 9).margin(1e-16));
    CHECK(largestGain(mesh, field, variance) <= kFlipGainThreshold);

    Mesh by_face_mesh = buildGridMesh(3, 2);
    const OptimizeStats by_face = optimizeSerial(by_face_mesh, field, {.cost = face});
    CHECK(by_face.flips == 1);
    CHECK(edgeBetween(by_face_mesh, 0, 5) != kNone);  // the new edge (0,0)–(2,1)
    CHECK(by_face.cost_final == Approx((1 + sqrt5) / 3).margin(1e-15));  // the SCF left: √5 + 1 on diagonal 0
    CHECK(largestGain(by_face_mesh, field, face) <= kFlipGainThreshold);
}

TEST_CASE("content cost: meshCost equals the paper's sum over triangles on any triangulation", "[content-cost]") {
    // meshCost sums edge shares in id order (face-SCF: SCF · (area_l + area_r) / 3; variance:
    // each triangle by its lowest-id edge); triangleFormCost sums area · weight per triangle,
    // computed independently. Sums of a few hundred terms below ~8: relative 1e-12.
    std::mt19937 rng(99);
    for (uint32_t channels : {1u, 3u, 4u}) {
        for (int round = 0; round < 4; ++round) {
            const Image image = test::randomImage(rng, 9, 7, channels, round % 2 ? 3 : 0);
            Mesh mesh = buildGridMesh(9, 7);
            test::flipRandomEdges(mesh, rng, 60);
            const CostField field = costFieldOf(image);
            for (CostFunction cost : kContentCosts) {
                INFO(costFunctionName(cost) << ", " << channels << " channels, round " << round);
                CHECK(meshCost(mesh, field, cost) == Approx(triangleFormCost(mesh, field, cost)).epsilon(1e-12));
            }
        }
    }
}

TEST_CASE("content cost: every triangle has area 1/2, so face-SCF is a third of Sederberg's", "[content-cost]") {
    // Pick's theorem (glsl/image/content_cost.h): a triangulation using every pixel centre has only
    // empty lattice triangles. Edge by edge, face-SCF's share is SCF · 2 / 6: 2 · SCF is exact,
    // so it rounds exactly as SCF / 3 does (one channel: no alpha share added).
    std::mt19937 rng(5);
    for (int round = 0; round < 6; ++round) {
        const Image image = test::randomImage(rng, 8, 8, round % 2 ? 3 : 1);
        Mesh mesh = buildGridMesh(8, 8);
        test::flipRandomEdges(mesh, rng, 200);
        for (const Triangle& t : listTriangles(mesh)) CHECK(test::twiceArea(mesh, t.v0, t.v1, t.v2) == 1);
        const CostField field = costFieldOf(image);
        for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
            const double scf = edgeCost(mesh, field, e, CostFunction::sederberg);
            CHECK(edgeCost(mesh, field, e, CostFunction::face_scf) == scf / 3);
        }
    }
}

TEST_CASE("content cost: flipGainOf equals the drop of meshCost, and flipping back negates it", "[content-cost]") {
    // Variance's flip changes e's two triangles only; face-SCF's the shares of e and its four
    // neighbours. The totals add ~130 shares, so they differ from the exact drop by ≲ 1e-14 ·
    // total: tolerance 1e-12 · (1 + total).
    std::mt19937 rng(4243);
    size_t tested = 0;
    for (uint32_t channels : {1u, 3u, 4u})
        for (int round = 0; round < 4; ++round) {
            const Image image = test::randomImage(rng, 7, 6, channels, round % 2 ? 3 : 0);
            Mesh mesh = buildGridMesh(7, 6);
            test::flipRandomEdges(mesh, rng, 30);
            const CostField field = costFieldOf(image);
            for (CostFunction cost : kContentCosts) {
                const double total = meshCost(mesh, field, cost);
                for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
                    const double gain = flipGainOf(mesh, field, e, cost);
                    CHECK((gain == kMinusInfinity) == !test::quadIsStrictlyConvex(mesh, e));
                    if (gain == kMinusInfinity) continue;
                    INFO(costFunctionName(cost) << ", " << channels << " channels, round " << round << ", edge " << e);
                    Mesh flipped = mesh;
                    flipEdge(flipped, e);
                    CHECK(gain == Approx(total - meshCost(flipped, field, cost)).margin(1e-12 * (1 + total)));
                    CHECK(flipGainOf(flipped, field, e, cost) == Approx(-gain).margin(1e-14 * (1 + total)));
                    ++tested;
                }
            }
        }
    CHECK(tested > 400);
}

TEST_CASE("content cost: the serial optimizer lowers the cost to a local optimum", "[content-cost]") {
    for (const TestImage& test : testImages()) {
        const CostField field = costFieldOf(test.image);
        for (CostFunction cost : kContentCosts) {
            INFO(costFunctionName(cost) << " on " << test.label);
            Mesh mesh = buildGridMesh(test.image.width, test.image.height);
            bool monotone = false;
            const OptimizeStats stats = optimizeWatched(mesh, field, cost, monotone);
            CHECK(monotone);
            CHECK_FALSE(stats.capped);
            CHECK(stats.flips > 0);
            CHECK(stats.cost_final < stats.cost_init);
            CHECK(checkMesh(mesh) == "");
            CHECK(test::triangulationProblem(mesh) == "");
            // Brute force over every edge: none left above the threshold.
            CHECK(largestGain(mesh, field, cost) <= kFlipGainThreshold);
            // The reported costs are those recomputed from scratch, bit for bit, and the paper's
            // sums over triangles up to rounding.
            CHECK(stats.cost_init == meshCost(buildGridMesh(test.image.width, test.image.height), field, cost));
            CHECK(stats.cost_final == meshCost(mesh, field, cost));
            CHECK(stats.cost_final == Approx(triangleFormCost(mesh, field, cost)).epsilon(1e-12));
        }
    }
}

namespace {

// Paper Fig. 3 as written, with `cost`: every sweep tests every edge in id order.
Mesh plainLawson(Mesh mesh, const CostField& field, CostFunction cost, uint64_t& flips, uint32_t& sweeps) {
    bool flipped = true;
    flips = 0;
    sweeps = 0;
    while (flipped) {
        flipped = false;
        for (uint32_t e = 0; e < mesh.edgeCount(); ++e)
            if (flipGainOf(mesh, field, e, cost) > kFlipGainThreshold) {
                flipEdge(mesh, e);
                ++flips;
                flipped = true;
            }
        ++sweeps;
    }
    return mesh;
}

}  // namespace

TEST_CASE("content cost: skipping edges outside each cost's ROI flips exactly like testing every edge",
          "[content-cost]") {
    // optimizeSerial re-tests only the closed ROI of each flip (variance: the closed 1-region)
    // and computes gains from kept shares; both must change nothing.
    std::mt19937 rng(8675310);
    std::vector<TestImage> images = testImages();
    for (int i = 0; i < 12; ++i) {
        const uint32_t w = 2 + uint32_t(rng() % 24), h = 2 + uint32_t(rng() % 16);
        std::ostringstream label;
        label << "random " << w << "x" << h;
        images.push_back({label.str(), test::randomImage(rng, w, h, 1 + i % 4, i % 3 == 0 ? 0 : 2 + i % 5)});
    }
    for (const TestImage& test : images) {
        const CostField field = costFieldOf(test.image);
        for (CostFunction cost : kContentCosts) {
            INFO(costFunctionName(cost) << " on " << test.label);
            uint64_t flips = 0;
            uint32_t sweeps = 0;
            const Mesh grid = buildGridMesh(test.image.width, test.image.height);
            const Mesh expected = plainLawson(grid, field, cost, flips, sweeps);
            Mesh mesh = grid;
            const OptimizeStats stats = optimizeSerial(mesh, field, {.cost = cost});
            CHECK(test::sameRecords(mesh, expected));
            CHECK(stats.flips == flips);
            CHECK(stats.iterations == sweeps);
        }
    }
}

TEST_CASE("content cost: the CPU backend and its twins optimise for the cost they were given", "[content-cost]") {
    const Image image = readImage(test::testDataPath("crop32_astronaut.png"));
    const CostField field = costFieldOf(image);
    for (CostFunction cost : kAllCosts) {
        INFO(costFunctionName(cost));
        Mesh expected = buildGridMesh(image.width, image.height);
        const OptimizeStats reference = optimizeSerial(expected, field, {.cost = cost});
        std::unique_ptr<Backend> backend = makeCpuBackend({.cost = cost});
        std::unique_ptr<Backend> twin = backend->twin();
        for (Backend* b : {backend.get(), twin.get()}) {
            b->prepare(image);
            const OptimizeStats stats = b->optimize();
            CHECK(test::sameRecords(b->mesh(), expected));
            CHECK(stats.cost_final == reference.cost_final);
            CHECK(stats.flips == reference.flips);
        }
    }
}

// ---- The Vulkan backend on lavapipe, against the serial reference's formulas ----

namespace {

// As test_vulkan.cpp: gains are computed in fp64 by the same code (glsl/image/sederberg.h,
// glsl/image/content_cost.h) on both sides, but a device may round division and square root
// differently in the last bit; a gain sums at most ten terms below ~8, so such differences
// stay far below 1e-12.
const double kGainTolerance = 1e-12;

VulkanBackend makeVulkan(const std::string& rule, CostFunction cost, bool active_set = true) {
    VulkanOptions options;
    options.rule = rule;
    options.cost = cost;
    options.active_set = active_set;
    options.validation = true;
    return VulkanBackend(options);
}

}  // namespace

TEST_CASE("content cost: Vulkan yields a valid mesh, locally optimal under core's gain, for every rule",
          "[content-cost][vulkan]") {
    const std::vector<TestImage> images = testImages();
    for (CostFunction cost : kContentCosts)
        for (const std::string& rule : tableFlipRules()) {
            VulkanBackend backend = makeVulkan(rule, cost);
            for (const TestImage& test : images) {
                INFO(costFunctionName(cost) << ", " << rule << " on " << test.label);
                backend.prepare(test.image);
                const OptimizeStats stats = backend.optimize();
                const Mesh mesh = backend.mesh();
                const CostField field = costFieldOf(test.image);
                CHECK(checkMesh(mesh) == "");
                CHECK_FALSE(stats.capped);
                CHECK(stats.flips > 0);
                CHECK(stats.cost_final < stats.cost_init);
                CHECK(largestGain(mesh, field, cost) <= kFlipGainThreshold + kGainTolerance);
                // The device's cost sums agree with core's on both meshes (summation order differs).
                CHECK(stats.cost_init ==
                      Approx(meshCost(buildGridMesh(test.image.width, test.image.height), field, cost)).epsilon(1e-12));
                CHECK(stats.cost_final == Approx(meshCost(mesh, field, cost)).epsilon(1e-12));
            }
            CHECK(backend.validationMessages() == 0);
        }
}

TEST_CASE("content cost: the kernels' edge shares equal core's", "[content-cost][vulkan]") {
    for (CostFunction cost : kContentCosts) {
        VulkanBackend backend = makeVulkan("localmax", cost);
        for (const TestImage& test : testImages()) {
            INFO(costFunctionName(cost) << " on " << test.label);
            backend.prepare(test.image);
            backend.optimize();  // on an optimised mesh, where flipped edges are long and slanted
            const Mesh mesh = backend.mesh();
            const CostField field = costFieldOf(test.image);
            const std::vector<double> device = backend.deviceEdgeCosts();
            double worst = 0.0;
            for (uint32_t e = 0; e < mesh.edgeCount(); ++e)
                worst = std::max(worst, std::abs(device[e] - edgeCost(mesh, field, e, cost)));
            // Same formula and operation order, contraction forbidden: only a last-bit difference
            // in the device's division or square root could remain (shares are below ~8).
            CHECK(worst <= 1e-14);
        }
        CHECK(backend.validationMessages() == 0);
    }
}

TEST_CASE("content cost: Vulkan's accepted flips never touch what another accepted gain read",
          "[content-cost][vulkan]") {
    // Each iteration: no accepted edge in another's conflict region (the 2-region, ExpROI the
    // 3-region, for every cost: glsl/image/select.comp), and — the property itself — the accepted
    // edges flipped one after another on the host, each gain recomputed by core just before its
    // own flip, equal the candidate step's gains: no flip changed what another's gain read.
    const std::vector<TestImage> images = testImages();
    for (CostFunction cost : kContentCosts)
        for (const char* rule : {"basic", "exproi", "maxgain", "exproi2-maxgain", "localmax"}) {
            const FlipRule flip_rule = *parseFlipRule(rule);
            VulkanBackend backend = makeVulkan(rule, cost);
            for (const TestImage& test : images) {
                INFO(costFunctionName(cost) << ", " << rule << " on " << test.label);
                backend.prepare(test.image);
                const CostField field = costFieldOf(test.image);
                Mesh expected_next;
                uint32_t iterations = 0;
                backend.optimizeStepwise([&](const IterationSnapshot& snapshot) {
                    ++iterations;
                    if (snapshot.iteration > 0) CHECK(test::sameRecords(snapshot.mesh, expected_next));
                    const int degree = snapshot.iteration < flip_rule.exproi_iterations ? 3 : 2;
                    const std::vector<uint32_t>& accepted = snapshot.accepted;
                    REQUIRE_FALSE(accepted.empty());
                    for (uint32_t e : accepted)
                        for (uint32_t f : regionOf(snapshot.mesh, e, degree))
                            CHECK_FALSE(std::binary_search(accepted.begin(), accepted.end(), f));
                    // Every candidate's gain is core's on the iteration's mesh.
                    for (size_t i = 0; i < snapshot.candidates.size(); ++i)
                        CHECK(std::abs(flipGainOf(snapshot.mesh, field, snapshot.candidates[i], cost) -
                                       snapshot.candidate_gains[i]) <= kGainTolerance);
                    Mesh mesh = snapshot.mesh;
                    double gain_sum = 0.0;
                    const double cost_before = meshCost(mesh, field, cost);
                    for (uint32_t e : accepted) {
                        const size_t i = std::lower_bound(snapshot.candidates.begin(), snapshot.candidates.end(), e) -
                                         snapshot.candidates.begin();
                        CHECK(std::abs(flipGainOf(mesh, field, e, cost) - snapshot.candidate_gains[i]) <=
                              kGainTolerance);
                        gain_sum += snapshot.candidate_gains[i];
                        flipEdge(mesh, e);
                    }
                    CHECK(meshCost(mesh, field, cost) == Approx(cost_before - gain_sum).epsilon(1e-12).margin(1e-12));
                    CHECK(checkMesh(mesh) == "");
                    expected_next = std::move(mesh);
                });
                CHECK(iterations > 0);
                CHECK(test::sameRecords(backend.mesh(), expected_next));
            }
            CHECK(backend.validationMessages() == 0);
        }
}

TEST_CASE("content cost: Vulkan's active set (each cost's closed ROI) changes nothing but the work",
          "[content-cost][vulkan]") {
    const std::vector<TestImage> images = testImages();
    for (CostFunction cost : kContentCosts)
        for (const char* rule : {"basic", "exproi-maxgain", "localmax"}) {
            VulkanBackend with = makeVulkan(rule, cost, true);
            VulkanBackend without = makeVulkan(rule, cost, false);
            for (const TestImage& test : images) {
                INFO(costFunctionName(cost) << ", " << rule << " on " << test.label);
                with.prepare(test.image);
                without.prepare(test.image);
                const OptimizeStats a = with.optimize();
                const OptimizeStats b = without.optimize();
                CHECK(test::sameRecords(with.mesh(), without.mesh()));
                CHECK(a.flips == b.flips);
                CHECK(a.iterations == b.iterations);
                CHECK(a.rounds == b.rounds);
            }
            CHECK(with.validationMessages() == 0);
            CHECK(without.validationMessages() == 0);
        }
}
