#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "cost.h"
#include "flip_gains.h"
#include "lawson.h"
#include "mesh.h"
#include "render.h"
#include "test_support.h"
#include "image_file.h"

using ddt::kNone;
using ddt::test::edgeBetween;
using ddt::test::makeImage;

namespace {

// Pixels with x + y < k are `dark`, the others `bright`.
ddt::Image antiDiagonalStep(uint32_t width, uint32_t height, uint32_t k, float dark, float bright) {
    std::vector<float> pixels;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) pixels.push_back(x + y < k ? dark : bright);
    return makeImage(width, height, 1, pixels);
}

// Whether cell (x, y) is split by its anti-diagonal (x+1, y)–(x, y+1) rather than the
// initial (x, y)–(x+1, y+1).
bool hasAntiDiagonal(const ddt::Mesh& mesh, uint32_t x, uint32_t y) {
    const uint32_t w = mesh.width;
    return edgeBetween(mesh, y * w + x + 1, (y + 1) * w + x) != kNone;
}

// Whether every unit edge of the grid (horizontal and vertical) is still in the mesh.
bool keepsAxisEdges(const ddt::Mesh& mesh) {
    const uint32_t w = mesh.width, h = mesh.height;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            if (x + 1 < w && edgeBetween(mesh, y * w + x, y * w + x + 1) == kNone) return false;
            if (y + 1 < h && edgeBetween(mesh, y * w + x, (y + 1) * w + x) == kNone) return false;
        }
    return true;
}

// Number of edges whose main vertices differ between two meshes (= flips in one sweep: each
// edge is tested once per sweep, and a flip always gives it two new main vertices).
uint64_t changedEdges(const ddt::Mesh& before, const ddt::Mesh& after) {
    uint64_t changed = 0;
    for (uint32_t e = 0; e < before.edgeCount(); ++e) {
        const ddt::EdgeVertices &u = before.vertices[e], &v = after.vertices[e];
        const bool same = (u.a == v.a && u.b == v.b) || (u.a == v.b && u.b == v.a);
        changed += !same;
    }
    return changed;
}

// Runs optimizeSerial and checks its invariants after every sweep and at the end.
ddt::OptimizeStats optimizeChecked(ddt::Mesh& mesh, const ddt::CostField& field, const std::string& name) {
    INFO(name);
    const double initial_cost = ddt::meshCost(mesh, field);
    ddt::Mesh previous = mesh;
    double previous_cost = initial_cost;
    uint64_t flips = 0, last_sweep_flips = 0;
    uint32_t sweeps = 0;
    bool valid = true, monotone = true, counted = true;
    ddt::LawsonOptions options;
    options.after_sweep = [&](uint32_t sweep, const ddt::Mesh& now) {
        counted = counted && sweep == sweeps + 1;
        sweeps = sweep;
        const std::string problem = ddt::checkMesh(now);
        const std::string independent = ddt::test::triangulationProblem(now);
        if (!problem.empty() || !independent.empty()) {
            UNSCOPED_INFO("sweep " << sweep << ": " << problem << " / " << independent);
            valid = false;
        }
        // Every flip lowers the exact cost by more than kFlipGainThreshold; meshCost itself
        // rounds by ≲ edges · 2^-53 relative (≲ 2e-13 for 1500 edges), hence the tolerance.
        const double cost = ddt::meshCost(now, field);
        if (cost > previous_cost + 1e-12 * (1.0 + std::abs(previous_cost))) {
            UNSCOPED_INFO("sweep " << sweep << ": cost rose from " << previous_cost << " to " << cost);
            monotone = false;
        }
        last_sweep_flips = changedEdges(previous, now);
        flips += last_sweep_flips;
        previous = now;
        previous_cost = cost;
    };
    const ddt::OptimizeStats stats = ddt::optimizeSerial(mesh, field, options);
    CHECK(valid);
    CHECK(monotone);
    CHECK(counted);
    CHECK_FALSE(stats.capped);
    CHECK(stats.iterations == sweeps);
    CHECK(stats.flips == flips);
    CHECK(last_sweep_flips == 0);  // the last sweep found nothing to flip
    CHECK(stats.cost_init == initial_cost);
    CHECK(stats.cost_final == ddt::meshCost(mesh, field));
    CHECK(stats.cost_final <= stats.cost_init + 1e-12 * (1.0 + std::abs(stats.cost_init)));
    // Locally optimal: no edge left whose gain exceeds the threshold.
    uint32_t improvable = 0;
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) improvable += ddt::flipGainOf(mesh, field, e) > ddt::kFlipGainThreshold;
    CHECK(improvable == 0);
    return stats;
}

}  // namespace

TEST_CASE("lawson: flips the diagonals across an anti-diagonal step edge") {
    // 6×6, pixels with x + y < 6 dark. Every cell whose corners straddle the step (top-left
    // corner sum x + y = 4 or 5) needs its anti-diagonal, so each sloped triangle spans one
    // step of the staircase and all sloped triangles share the gradient 0.5·(1, 1).
    //
    //   values (. = 0.25, # = 0.75)       expected mesh, cell diagonals
    //     . . . . . .                     | \ \ \ \ / |
    //     . . . . . #                     | \ \ \ / / |
    //     . . . . # #                     | \ \ / / \ |
    //     . . . # # #                     | \ / / \ \ |
    //     . . # # # #                     | / / \ \ \ |
    //     . # # # # #
    //
    // Initial cost, by hand: a cell with corner sum s has the upper-right gradient
    // (J(s), J(s+1)) and lower-left (J(s+1), J(s)), where J(t) = 0.5 if t = 5 else 0. The
    // diagonal of each of the 9 straddling cells sees (0.5, 0) against (0, 0.5): SCF 0.25.
    // Every unit edge separates parallel or flat gradients: 0. Total 9 · 0.25 = 2.25.
    const float dark = 0.25f, bright = 0.75f;
    ddt::Image image = antiDiagonalStep(6, 6, 6, dark, bright);
    ddt::Mesh mesh = ddt::buildGridMesh(6, 6);
    const ddt::Mesh initial = mesh;
    ddt::CostField field = ddt::costFieldOf(image);
    ddt::OptimizeStats stats = optimizeChecked(mesh, field, "anti-diagonal step");
    CHECK(stats.cost_init == 2.25);
    // The sloped triangles' gradients are parallel, but |g|·|g| − g·g rounds: sqrt(0.5)² ≠ 0.5.
    CHECK(std::abs(stats.cost_final) < 1e-12);
    CHECK(stats.flips == 9);  // each straddling diagonal once, nothing else
    CHECK(stats.iterations == 2);
    CHECK(keepsAxisEdges(mesh));
    for (uint32_t y = 0; y < 5; ++y)
        for (uint32_t x = 0; x < 5; ++x) {
            INFO("cell " << x << ", " << y);
            CHECK(hasAntiDiagonal(mesh, x, y) == (x + y == 4 || x + y == 5));
        }

    // Rendered ×4 the edge is sharp: the surface is dark for u + v ≤ 5, bright for u + v ≥ 6
    // and linear in between. Output pixel X samples u = (X + 0.5)/4 − 0.5 = (2X − 3)/8,
    // clamped into [0, 5]; in eighths U = clamp(2X − 3, 0, 40).
    const ddt::OutputSize out{24, 24};
    auto eighths = [](int64_t index) { return std::clamp<int64_t>(2 * index - 3, 0, 40); };
    auto sharpness = [&](const ddt::Mesh& m, bool& plateaus_exact, bool& ramp_linear) {
        const ddt::Image rendered = ddt::renderImage(m, image, out);
        plateaus_exact = ramp_linear = true;
        for (uint32_t y = 0; y < out.height; ++y)
            for (uint32_t x = 0; x < out.width; ++x) {
                const int64_t s = eighths(x) + eighths(y);  // (u + v) · 8
                const float value = rendered.pixels[y * out.width + x];
                if (s <= 40) plateaus_exact &= value == dark;
                else if (s >= 48) plateaus_exact &= value == bright;
                // Between: 0.25 + 0.5·(u + v − 5); float output, so within 1e-6.
                else ramp_linear &= std::abs(value - (0.25 + 0.5 * (s - 40) / 8.0)) < 1e-6;
            }
    };
    bool plateaus_exact = false, ramp_linear = false;
    sharpness(mesh, plateaus_exact, ramp_linear);
    CHECK(plateaus_exact);
    CHECK(ramp_linear);
    // The initial mesh smears the step across the straddling cells' diagonals.
    sharpness(initial, plateaus_exact, ramp_linear);
    CHECK_FALSE(plateaus_exact);
}

TEST_CASE("lawson: a flat image needs no flip") {
    ddt::Image image = makeImage(5, 4, 3, std::vector<float>(5 * 4 * 3, 0.5f));
    ddt::Mesh mesh = ddt::buildGridMesh(5, 4);
    const ddt::Mesh initial = mesh;
    ddt::OptimizeStats stats = ddt::optimizeSerial(mesh, ddt::costFieldOf(image));
    CHECK(stats.flips == 0);
    CHECK(stats.iterations == 1);
    CHECK(stats.cost_init == 0.0);
    CHECK(stats.cost_final == 0.0);
    CHECK(ddt::test::sameRecords(mesh, initial));
}

TEST_CASE("lawson: step edges along the grid need no flip (fixtures)") {
    // step8_gray: columns 0–3 black, 4–7 white. The straddling cells' triangles both have the
    // gradient (1, 0), every other triangle is flat: cost 0.
    // diag16_rgb: the edge runs along x = y, the direction of the initial diagonals.
    for (const char* name : {"step8_gray.png", "diag16_rgb.png"}) {
        INFO(name);
        ddt::Image image = ddt::readImage(ddt::test::testDataPath(name));
        ddt::Mesh mesh = ddt::buildGridMesh(image.width, image.height);
        const ddt::Mesh initial = mesh;
        ddt::OptimizeStats stats = ddt::optimizeSerial(mesh, ddt::costFieldOf(image));
        CHECK(stats.flips == 0);
        // Parallel gradients cost 0 up to the rounding of |g1|·|g2| − g1·g2.
        CHECK(std::abs(stats.cost_init) < 1e-12);
        CHECK(ddt::test::sameRecords(mesh, initial));
    }
}

TEST_CASE("lawson: a non-convex quadrilateral is never flipped") {
    // The dart of the cost test: on 4×3, after flipping 1–5 and 4–5, the edge 0–5 (id 2, the
    // first edge a sweep tests that has two triangles) has the quad 0, 6, 5, 9, reflex at 5.
    // The values make its flip to 6–9 look profitable if convexity were ignored.
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
    for (auto [p, q] : {std::pair{1u, 5u}, {4u, 5u}}) ddt::flipEdge(mesh, edgeBetween(mesh, p, q));
    REQUIRE(ddt::checkMesh(mesh) == "");
    REQUIRE(edgeBetween(mesh, 0, 5) == 2);
    std::vector<float> values(12, 0.0f);
    values[6] = values[9] = 1.0f;
    ddt::Image image = makeImage(4, 3, 1, values);
    ddt::CostField field = ddt::costFieldOf(image);
    const ddt::FlipStencil s = ddt::flipStencil(mesh, 2);
    REQUIRE_FALSE(ddt::flipIsConvex(s, ddt::placesOf(mesh)));
    auto at = [&](uint32_t vertex) { return vertex == kNone ? 0.0f : values[vertex]; };
    const ddt::StencilValues z{at(s.a), at(s.b), at(s.l), at(s.r), at(s.far_bl), at(s.far_la), at(s.far_ar), at(s.far_rb)};
    // The gain formula alone, without the convexity test, "wants" the flip.
    REQUIRE(ddt::flipGain(s, z, ddt::placesOf(mesh)) > ddt::kFlipGainThreshold);

    ddt::LawsonOptions one_sweep;
    one_sweep.max_sweeps = 1;
    ddt::optimizeSerial(mesh, field, one_sweep);
    // Edge 2 was tested first, while still a dart; neighbours' flips can change its l and r
    // but never its main vertices.
    const ddt::EdgeVertices v = mesh.vertices[2];
    CHECK(((v.a == 0 && v.b == 5) || (v.a == 5 && v.b == 0)));
    CHECK(ddt::checkMesh(mesh) == "");
}

TEST_CASE("lawson: invariants hold on seeded random images") {
    // 30 images from 2×2 to 24×17, 1–4 channels, continuous values or 2–5 levels (levels
    // make many exactly equal gains, the case the threshold exists for).
    std::mt19937 rng(123456789);
    for (int i = 0; i < 30; ++i) {
        const uint32_t w = 2 + uint32_t(i * 22 / 29), h = 2 + uint32_t((i * 7) % 16);
        const uint32_t channels = 1 + i % 4;
        const uint32_t levels = i % 3 == 0 ? 0 : 2 + i % 4;
        ddt::Image image = ddt::test::randomImage(rng, w, h, channels, levels);
        ddt::Mesh mesh = ddt::buildGridMesh(w, h);
        std::ostringstream name;
        name << "image " << i << ": " << w << "x" << h << ", " << channels << " channels, levels " << levels;
        optimizeChecked(mesh, ddt::costFieldOf(image), name.str());
    }
}

TEST_CASE("lawson: invariants hold on a real photo crop") {
    ddt::Image image = ddt::readImage(ddt::test::testDataPath("crop32_astronaut.png"));
    REQUIRE(image.width == 32);
    REQUIRE(image.height == 32);
    ddt::Mesh mesh = ddt::buildGridMesh(32, 32);
    ddt::OptimizeStats stats = optimizeChecked(mesh, ddt::costFieldOf(image), "crop32_astronaut");
    CHECK(stats.flips > 0);
    CHECK(stats.cost_final < stats.cost_init);
}

TEST_CASE("lawson: the sweep cap stops early and says so") {
    ddt::Image image = ddt::readImage(ddt::test::testDataPath("crop32_astronaut.png"));
    ddt::CostField field = ddt::costFieldOf(image);
    ddt::Mesh mesh = ddt::buildGridMesh(32, 32);
    ddt::LawsonOptions options;
    options.max_sweeps = 2;
    uint32_t calls = 0;
    options.after_sweep = [&](uint32_t, const ddt::Mesh&) { ++calls; };
    ddt::OptimizeStats stats = ddt::optimizeSerial(mesh, field, options);
    CHECK(stats.capped);
    CHECK(stats.iterations == 2);
    CHECK(calls == 2);
    CHECK(ddt::checkMesh(mesh) == "");
}

namespace {

// Paper Fig. 3 as written: every sweep tests every edge in id order. optimizeSerial skips the
// edges whose gain cannot have changed, and a flipped edge until a flip beside it (its gain
// would be that of undoing it); it must flip exactly the same edges in the same order.
ddt::OptimizeStats plainLawson(ddt::Mesh& mesh, const ddt::CostField& field, ddt::CostFunction cost,
                               std::vector<ddt::Mesh>& after_sweeps) {
    ddt::OptimizeStats stats;
    stats.cost_init = ddt::meshCost(mesh, field, cost);
    bool flipped = true;
    while (flipped) {
        flipped = false;
        for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
            if (ddt::flipGainOf(mesh, field, e, cost) > ddt::kFlipGainThreshold) {
                ddt::flipEdge(mesh, e);
                ++stats.flips;
                flipped = true;
            }
        }
        ++stats.iterations;
        after_sweeps.push_back(mesh);
    }
    stats.cost_final = ddt::meshCost(mesh, field, cost);
    return stats;
}

void checkSameAsPlainSweeps(const ddt::Mesh& initial, const ddt::CostField& field, const std::string& name,
                            ddt::CostFunction cost = ddt::CostFunction::sederberg) {
    INFO(name << ", " << ddt::costFunctionName(cost));
    ddt::Mesh plain = initial;
    ddt::Mesh fast = initial;
    std::vector<ddt::Mesh> plain_sweeps, fast_sweeps;
    const ddt::OptimizeStats expected = plainLawson(plain, field, cost, plain_sweeps);
    ddt::LawsonOptions options;
    options.cost = cost;
    options.after_sweep = [&](uint32_t, const ddt::Mesh& mesh) { fast_sweeps.push_back(mesh); };
    const ddt::OptimizeStats stats = ddt::optimizeSerial(fast, field, options);
    CHECK(stats.flips == expected.flips);
    CHECK(stats.iterations == expected.iterations);
    CHECK(stats.cost_init == expected.cost_init);
    CHECK(stats.cost_final == expected.cost_final);
    REQUIRE(fast_sweeps.size() == plain_sweeps.size());
    for (size_t i = 0; i < plain_sweeps.size(); ++i) {
        INFO("after sweep " << i + 1);
        CHECK(ddt::test::sameRecords(fast_sweeps[i], plain_sweeps[i]));
    }
    CHECK(ddt::test::sameRecords(fast, plain));
}

void checkSameAsPlainSweeps(const ddt::Image& image, const std::string& name,
                            ddt::CostFunction cost = ddt::CostFunction::sederberg) {
    checkSameAsPlainSweeps(ddt::buildGridMesh(image.width, image.height), ddt::costFieldOf(image), name, cost);
}

}  // namespace

TEST_CASE("lawson: skipping unchanged edges flips exactly like testing every edge") {
    std::mt19937 rng(8675309);
    for (int i = 0; i < 24; ++i) {
        const uint32_t w = 2 + uint32_t(rng() % 30), h = 2 + uint32_t(rng() % 20);
        const uint32_t channels = 1 + i % 4, levels = i % 3 == 0 ? 0 : 2 + i % 5;
        std::ostringstream name;
        name << "random " << i << ": " << w << "x" << h << ", " << channels << " channels, levels " << levels;
        // Every cost: Sederberg's on most, face-SCF and variance on every third.
        const ddt::CostFunction cost = i % 3 == 1 ? ddt::CostFunction::face_scf
                                       : i % 6 == 2 ? ddt::CostFunction::variance
                                                    : ddt::CostFunction::sederberg;
        checkSameAsPlainSweeps(ddt::test::randomImage(rng, w, h, channels, levels), name.str(), cost);
    }
    const ddt::Image crop = ddt::readImage(ddt::test::testDataPath("crop32_astronaut.png"));
    for (ddt::CostFunction cost : {ddt::CostFunction::sederberg, ddt::CostFunction::face_scf})
        checkSameAsPlainSweeps(crop, "crop32_astronaut", cost);
    checkSameAsPlainSweeps(antiDiagonalStep(9, 7, 8, 0.0f, 1.0f), "anti-diagonal step");
    // A mesh off the grid (explicit positions): long and thin triangles, costs far from 1.
    for (int i = 0; i < 4; ++i) {
        const ddt::Image image = ddt::test::randomImage(rng, 20, 14, 1 + i % 3, 0);
        checkSameAsPlainSweeps(ddt::test::movedMesh(20, 14, rng), ddt::costFieldOf(image), "moved mesh",
                               i % 2 ? ddt::CostFunction::face_scf : ddt::CostFunction::sederberg);
    }
}

// What lets a sweep skip a flipped edge: FlipGains::flipped returns the gain of flipping the
// edge back, which must be flipGainOf of the flipped mesh bit for bit, whatever the cost
// (variance keeps no costs and says it does not know), channels or places.
TEST_CASE("lawson: a flip's returned gain is the flipped edge's gain, bit for bit") {
    std::mt19937 rng(4711);
    for (int i = 0; i < 12; ++i) {
        const ddt::CostFunction cost = i % 3 == 0 ? ddt::CostFunction::sederberg
                                       : i % 3 == 1 ? ddt::CostFunction::face_scf
                                                    : ddt::CostFunction::variance;
        const ddt::Image image = ddt::test::randomImage(rng, 18, 13, 1 + i % 4, i % 2 ? 3 : 0);
        ddt::Mesh mesh = i < 6 ? ddt::buildGridMesh(18, 13) : ddt::test::movedMesh(18, 13, rng);
        const ddt::CostField field = ddt::costFieldOf(image);
        INFO(ddt::costFunctionName(cost) << ", case " << i);
        ddt::FlipGains gains(mesh, field, cost);
        int flips = 0;
        for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
            if (gains.gainOf(e) <= ddt::kFlipGainThreshold) continue;
            ddt::flipEdge(mesh, e);
            const double back = gains.flipped(e);
            ++flips;
            if (cost == ddt::CostFunction::variance) {
                CHECK(back == std::numeric_limits<double>::infinity());
                continue;
            }
            CHECK(back == ddt::flipGainOf(mesh, field, e, cost));
            CHECK(back <= ddt::kFlipGainThreshold);
        }
        CHECK(flips > 0);
    }
}
