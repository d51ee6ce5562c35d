// Meshes of known pixels (--mask): the convex-hull check, and both optimizers on them — the
// serial reference, and the Vulkan rule checked step by step against core's gains and flips.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include "cost.h"
#include "delaunay.h"
#include "lawson.h"
#include "mesh.h"
#include "sampled_render.h"
#include "stepwise_check.h"
#include "test_support.h"
#include "vulkan_backend.h"

namespace {

using namespace ddt;

// About `share` of a width × height image's pixels, at random.
std::vector<uint32_t> randomPixels(uint32_t width, uint32_t height, double share, uint32_t seed) {
    std::mt19937 rng(seed);
    std::bernoulli_distribution known(share);
    std::vector<uint32_t> ids;
    for (uint32_t v = 0; v < width * height; ++v)
        if (known(rng)) ids.push_back(v);
    return ids;
}

}  // namespace

TEST_CASE("sampled mesh: a Delaunay mesh of random pixels covers their convex hull, not the rectangle", "[delaunay]") {
    const Mesh mesh = delaunayOfPixels(30, 20, randomPixels(30, 20, 0.1, 1));
    CHECK(checkMesh(mesh, MeshHull::convex) == "");
    // Some corner is unknown for this seed, so the rectangle's rules fail.
    CHECK(checkMesh(mesh, MeshHull::rectangle) != "");
}

TEST_CASE("sampled mesh: checkMesh refuses a boundary that turns right", "[delaunay]") {
    // An L of three unit cells, six triangles: the boundary turns right at (1, 1).
    //   0 - 1 - 2
    //   | \ | \ |
    //   3 - 4 - 5
    //   | \ |
    //   6 - 7
    const uint32_t w = 3;
    auto id = [&](uint32_t x, uint32_t y) { return y * w + x; };
    const std::vector<uint32_t> triangles = {id(0, 0), id(1, 0), id(1, 1), id(0, 0), id(1, 1), id(0, 1),
                                             id(1, 0), id(2, 0), id(2, 1), id(1, 0), id(2, 1), id(1, 1),
                                             id(0, 1), id(1, 1), id(1, 2), id(0, 1), id(1, 2), id(0, 2)};
    const Mesh mesh = meshFromTriangles(w, 3, triangles);
    CHECK(checkMesh(mesh, MeshHull::convex) == "boundary is not convex");
}

TEST_CASE("sampled mesh: the serial optimizer keeps the hull and reaches a local optimum", "[delaunay]") {
    std::mt19937 rng(5);
    const Image image = test::randomImage(rng, 24, 18, 3);
    const CostField field = costFieldOf(image);
    for (CostFunction cost : {CostFunction::sederberg, CostFunction::variance, CostFunction::face_scf}) {
        Mesh mesh = delaunayOfPixels(24, 18, randomPixels(24, 18, 0.3, 2));
        LawsonOptions options;
        options.cost = cost;
        const OptimizeStats stats = optimizeSerial(mesh, field, options);
        CHECK(checkMesh(mesh, MeshHull::convex) == "");
        CHECK(stats.flips > 0);
        CHECK(stats.cost_final < stats.cost_init);
        CHECK(test::largestGain(mesh, field, cost) <= kFlipGainThreshold);
    }
}

TEST_CASE("sampled mesh: Vulkan's flips on a mesh of known pixels equal core's, step by step", "[delaunay][vulkan]") {
    std::mt19937 rng(6);
    const Image image = test::randomImage(rng, 26, 19, 3);
    for (CostFunction cost : {CostFunction::sederberg, CostFunction::variance, CostFunction::face_scf}) {
        INFO(costFunctionName(cost));
        test::checkVulkanStepwise(image, delaunayOfPixels(26, 19, randomPixels(26, 19, 0.25, 3)), cost);
    }
}

TEST_CASE("sampled mesh: every pixel known gives the grid's optimization on both backends", "[delaunay][vulkan]") {
    std::mt19937 rng(8);
    const Image image = test::randomImage(rng, 21, 16, 1);
    std::vector<uint32_t> all(21 * 16);
    for (uint32_t v = 0; v < all.size(); ++v) all[v] = v;
    std::unique_ptr<Backend> cpu = makeCpuBackend();
    VulkanOptions options;
    options.validation = true;
    VulkanBackend vulkan(options);
    for (Backend* backend : {cpu.get(), static_cast<Backend*>(&vulkan)}) {
        backend->prepare(image);
        backend->optimize();
        const Mesh from_grid = backend->mesh();
        backend->prepareFrom(image, delaunayOfPixels(21, 16, all));
        backend->optimize();
        CHECK(test::sameRecords(backend->mesh(), from_grid));
    }
    CHECK(vulkan.validationMessages() == 0);
}

TEST_CASE("sampled render: the hull is rendered linearly, the outside from the nearest pixel", "[delaunay]") {
    // Known: a triangle of pixels (2, 1), (6, 1), (2, 5) of an 8 × 7 image whose values are a
    // plane, so that inside the hull the output is the plane, and outside it repeats the hull.
    std::vector<float> pixels;
    for (uint32_t y = 0; y < 7; ++y)
        for (uint32_t x = 0; x < 8; ++x) pixels.push_back(0.05f * float(x) + 0.1f * float(y));
    const Image image = test::makeImage(8, 7, 1, pixels);
    const Mesh mesh = delaunayOfPixels(8, 7, {1 * 8 + 2, 1 * 8 + 6, 5 * 8 + 2});
    REQUIRE(checkMesh(mesh, MeshHull::convex) == "");
    const Image out = renderSampledMesh(mesh, image, {8, 7});
    for (uint32_t y = 0; y < 7; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            INFO(x << ", " << y);
            const float value = out.pixels[size_t(y) * 8 + x];
            CHECK_FALSE(std::isnan(value));
            // At ×1 the samples are the pixel centres; inside the closed triangle (x ≥ 2, y ≥ 1,
            // x + y ≤ 7) the plane (float weights: within 1e-6), outside the nearest such pixel's.
            int cx = int(x), cy = int(y);
            if (!(cx >= 2 && cy >= 1 && cx + cy <= 7)) {
                // Brute force over the triangle's pixels: least squared distance, then column, row.
                int best = INT32_MAX, bx = 0, by = 0;
                for (int qx = 2; qx <= 6; ++qx)
                    for (int qy = 1; qy <= 5; ++qy)
                        if (qx + qy <= 7 && (qx - cx) * (qx - cx) + (qy - cy) * (qy - cy) < best) {
                            best = (qx - cx) * (qx - cx) + (qy - cy) * (qy - cy);
                            bx = qx;
                            by = qy;
                        }
                cx = bx;
                cy = by;
            }
            CHECK(value == Approx(0.05 * cx + 0.1 * cy).margin(1e-6));
        }
}
