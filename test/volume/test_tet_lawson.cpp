#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tet_test_support.h"
#include "tet_cost.h"
#include "tet_flips.h"
#include "tet_lawson.h"
#include "tet_mesh.h"

using ddt::FlipKind;
using ddt::TetWeight;

using namespace ddt::test;

namespace {

// Runs the serial Lawson from the Kuhn mesh and checks its invariants after every iteration
// and at the end: a valid mesh, the cached cost equal to a recomputation from scratch and
// never rising, and no flip worth applying left.
ddt::TetLawsonStats optimizeChecked(ddt::TetMesh& mesh, const ddt::TetCostField& field, TetWeight weight) {
    INFO(ddt::tetWeightName(weight));
    const double initial_cost = ddt::meshCost(mesh, field, weight);
    double previous_cost = initial_cost;
    uint32_t iterations = 0;
    bool valid = true, exact = true, monotone = true, counted = true;
    ddt::TetLawsonOptions options;
    options.weight = weight;
    options.after_iteration = [&](uint32_t iteration, const ddt::TetMesh& now, double cost) {
        counted = counted && iteration == iterations + 1;
        iterations = iteration;
        const std::string problem = ddt::checkTetMesh(now);
        if (!problem.empty()) {
            UNSCOPED_INFO("iteration " << iteration << ": " << problem);
            valid = false;
        }
        exact = exact && cost == ddt::meshCost(now, field, weight);
        // Every flip lowers the exact cost; the compensated total rounds at ~1e-16.
        if (cost > previous_cost + 1e-13 * (1.0 + std::abs(previous_cost))) {
            UNSCOPED_INFO("iteration " << iteration << ": cost rose from " << previous_cost << " to " << cost);
            monotone = false;
        }
        previous_cost = cost;
    };
    const ddt::TetLawsonStats stats = ddt::optimizeTetMeshSerial(mesh, field, options);
    CHECK(valid);
    CHECK(exact);
    CHECK(monotone);
    CHECK(counted);
    CHECK_FALSE(stats.capped);
    CHECK(stats.iterations == iterations);
    CHECK(stats.cost_before == initial_cost);
    CHECK(stats.cost_after == ddt::meshCost(mesh, field, weight));
    CHECK(stats.cost_after <= stats.cost_before);
    // A local optimum: no tet has a flip worth applying.
    const ddt::TetCosts costs(mesh, field, weight);
    uint32_t improvable = 0;
    for (uint32_t t = 0; t < mesh.slotCount(); ++t)
        if (mesh.inUse(t)) improvable += ddt::bestFlipAt(mesh, costs, t).has_value();
    CHECK(improvable == 0);
    return stats;
}

}  // namespace

TEST_CASE("tet lawson: a sharp slanted plane lowers both costs", "[tet]") {
    for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
        const ddt::TetCostField field = slantedPlaneField(6, {0.8, 0.8, 2.0});
        ddt::TetMesh mesh = ddt::kuhnTetMesh(field.size);
        const ddt::TetLawsonStats stats = optimizeChecked(mesh, field, weight);
        CHECK(stats.flipCount() > 0);
        CHECK(stats.cost_after < 0.9 * stats.cost_before);
        CHECK(stats.iterations >= 2);  // the last iteration applies nothing
    }
}

TEST_CASE("tet lawson: a sphere: a second run does nothing, and runs are deterministic", "[tet]") {
    const ddt::TetCostField field = sphereField(6, 2.0);
    for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
        INFO(ddt::tetWeightName(weight));
        ddt::TetMesh mesh = ddt::kuhnTetMesh(field.size);
        const ddt::TetLawsonStats stats = optimizeChecked(mesh, field, weight);
        CHECK(stats.flipCount() > 0);
        CHECK(stats.cost_after < stats.cost_before);

        ddt::TetMesh again = mesh;
        ddt::TetLawsonOptions options;
        options.weight = weight;
        const ddt::TetLawsonStats second = ddt::optimizeTetMeshSerial(again, field, options);
        CHECK(second.flipCount() == 0);
        CHECK(second.iterations == 1);
        CHECK(second.cost_before == stats.cost_after);
        CHECK(second.cost_after == stats.cost_after);
        CHECK(sameMesh(again, mesh));

        ddt::TetMesh twin = ddt::kuhnTetMesh(field.size);
        const ddt::TetLawsonStats twin_stats = ddt::optimizeTetMeshSerial(twin, field, options);
        CHECK(sameMesh(twin, mesh));
        CHECK(twin_stats.flips == stats.flips);
        CHECK(twin_stats.cost_after == stats.cost_after);
    }
}

TEST_CASE("tet lawson: a linear field: face_scf is zero, variance is not", "[tet]") {
    // face_scf: every tet has the same gradient, so every face costs |g|² − g·g = 0 up to
    // rounding, and so does every gain: no flip passes the threshold.
    {
        const ddt::TetCostField field = fieldOf({5, 5, 5}, [](uint32_t x, uint32_t y, uint32_t z) { return x + 2.0 * y + 3.0 * z; },
                                                {0.5, 1.0, 1.5});
        ddt::TetMesh mesh = ddt::kuhnTetMesh(field.size);
        const ddt::TetLawsonStats stats = optimizeChecked(mesh, field, TetWeight::face_scf);
        CHECK(stats.flipCount() == 0);
        CHECK(stats.iterations == 1);
        CHECK(std::abs(stats.cost_before) < 1e-13);
    }
    // variance: a tet's variance of g·x is gᵀ C g, C the covariance of its vertices, and
    // content · C = 5 ∫ (x − c)(x − c)ᵀ over the tet (c its centroid), so the total is
    // 5 gᵀ (M − Σ content · c cᵀ) g with M the box's second moment: not zero, and lower when
    // the centroids spread along g.
    // f = x on 5³: the Kuhn walks hold x values {0 1 1 1}, {0 0 1 1}, {0 0 0 1}, two walks each:
    // variances 3/16, 4/16, 3/16, a cell 20/16 · 1/6 = 5/24 in steps of one; normalized by the
    // range 4, 5/24/16 per cell, 64 cells: 5/6. No flip at hand moves a centroid's x (the 4–4
    // at a face diagonal in z = const trades tets whose centroid x are 1/4, 1/2, 1/2, 3/4 for
    // the same), so the Kuhn mesh stays.
    {
        const ddt::TetCostField field = fieldOf({5, 5, 5}, [](uint32_t x, uint32_t, uint32_t) { return double(x); });
        ddt::TetMesh mesh = ddt::kuhnTetMesh(field.size);
        const ddt::TetMesh kuhn = mesh;
        const ddt::TetLawsonStats stats = optimizeChecked(mesh, field, TetWeight::variance);
        CHECK(stats.cost_before == Approx(5.0 / 6.0).epsilon(1e-14));
        CHECK(stats.flipCount() == 0);
        CHECK(sameMesh(mesh, kuhn));
    }
    // f = x + y on 5³: walks' values 0, c_a, c_a + c_b, 2 with c = (1, 1, 0): variances 11/16
    // (four walks) and 1/2 (two), a cell 60/16 · 1/6 = 5/8; normalized by the range 8,
    // 5/8/64 per cell, 64 cells: 5/8. Flips turn the tets along the planes x + y = const.
    {
        const ddt::TetCostField field = fieldOf({5, 5, 5}, [](uint32_t x, uint32_t y, uint32_t) { return double(x + y); });
        ddt::TetMesh mesh = ddt::kuhnTetMesh(field.size);
        const ddt::TetLawsonStats stats = optimizeChecked(mesh, field, TetWeight::variance);
        CHECK(stats.cost_before == Approx(5.0 / 8.0).epsilon(1e-14));
        CHECK(stats.flipCount() > 0);
        CHECK(stats.cost_after < 0.5 * stats.cost_before);
    }
}

TEST_CASE("tet lawson: a flat volume needs no flip", "[tet]") {
    for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
        const ddt::TetCostField field = fieldOf({4, 3, 5}, [](uint32_t, uint32_t, uint32_t) { return 1234.0; });
        ddt::TetMesh mesh = ddt::kuhnTetMesh(field.size);
        const ddt::TetMesh kuhn = mesh;
        const ddt::TetLawsonStats stats = optimizeChecked(mesh, field, weight);
        CHECK(stats.flipCount() == 0);
        CHECK(stats.iterations == 1);
        CHECK(stats.cost_before == 0.0);
        CHECK(sameMesh(mesh, kuhn));
    }
}

TEST_CASE("tet lawson: neither the data's range nor the physical unit changes the mesh", "[tet]") {
    // The same sphere as 8-bit data (0, 255) and as Hounsfield units (−1000, 3000), in
    // millimetres and in units 2^30 times larger (contents × 2^-90, gradients × 2^30, all
    // exact): the relative threshold and the normalization make the same decisions.
    const Size size = {6, 6, 6};
    auto sphere = [](double lo, double hi) {
        return [=](uint32_t x, uint32_t y, uint32_t z) {
            return (x - 2.5) * (x - 2.5) + (y - 2.5) * (y - 2.5) + (z - 2.5) * (z - 2.5) <= 4.0 ? hi : lo;
        };
    };
    const double tiny = std::ldexp(1.0, -30);
    for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
        INFO(ddt::tetWeightName(weight));
        ddt::TetLawsonOptions options;
        options.weight = weight;
        ddt::TetMesh bytes = ddt::kuhnTetMesh(size), hounsfield = bytes, small = bytes;
        const ddt::TetLawsonStats reference = ddt::optimizeTetMeshSerial(bytes, fieldOf(size, sphere(0, 255), {1.0, 1.0, 2.0}), options);
        ddt::optimizeTetMeshSerial(hounsfield, fieldOf(size, sphere(-1000, 3000), {1.0, 1.0, 2.0}), options);
        const ddt::TetLawsonStats scaled = ddt::optimizeTetMeshSerial(small, fieldOf(size, sphere(0, 255), {tiny, tiny, 2 * tiny}), options);
        CHECK(reference.flipCount() > 0);
        CHECK(sameMesh(bytes, hounsfield));
        CHECK(sameMesh(bytes, small));
        const double unit = weight == TetWeight::variance ? std::ldexp(1.0, -90) : std::ldexp(1.0, -30);
        CHECK(scaled.cost_after == reference.cost_after * unit);
    }
}

TEST_CASE("tet lawson: the iteration cap stops early and says so", "[tet]") {
    const ddt::TetCostField field = slantedPlaneField(6);
    ddt::TetMesh mesh = ddt::kuhnTetMesh(field.size);
    ddt::TetLawsonOptions options;
    options.weight = TetWeight::variance;
    options.max_iterations = 1;
    const ddt::TetLawsonStats stats = ddt::optimizeTetMeshSerial(mesh, field, options);
    CHECK(stats.capped);
    CHECK(stats.iterations == 1);
    CHECK(stats.flipCount() > 0);
    CHECK(ddt::checkTetMesh(mesh) == "");
    CHECK(stats.cost_after == ddt::meshCost(mesh, field, TetWeight::variance));
}
