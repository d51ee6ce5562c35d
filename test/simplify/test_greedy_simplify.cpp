// The serial greedy simplifier (core/simplify/greedy_simplify.h): targets reached with a valid
// mesh, the same result every run, and the collapse order the quadrics call for.
#include <catch2/catch.hpp>

#include <random>

#include "cost.h"
#include "greedy_simplify.h"
#include "lawson.h"
#include "test_support.h"

using namespace ddt;
using namespace ddt::test;

TEST_CASE("greedy simplify: reaches each target with a valid mesh, the same every run") {
    const Image photo = photoPiece();
    const Mesh optimised = optimisedGridMesh(photo);
    const uint32_t all = photo.width * photo.height;
    for (double fraction : {0.5, 0.1, 0.02}) {
        INFO("fraction " << fraction);
        const uint32_t target = uint32_t(fraction * all);
        Mesh mesh = optimised, again = optimised;
        Image values = photo, values_again = photo;
        const SimplifyStats stats = simplifySerial(mesh, values, target);
        simplifySerial(again, values_again, target);
        CHECK(checkMesh(mesh) == "");
        CHECK(usedVertexCount(mesh) == target);
        CHECK(stats.vertices_before == all);
        CHECK(stats.vertices_after == target);
        CHECK(stats.collapses == all - target);
        CHECK(sameRecords(mesh, again));
        CHECK(samePixels(values.pixels, values_again.pixels));
        for (float value : values.pixels) CHECK((value >= 0.0f && value <= 1.0f));
    }
}

TEST_CASE("greedy simplify: a flat picture keeps only its corners") {
    Image flat = makeImage(9, 7, 3, std::vector<float>(9 * 7 * 3, 0.25f));
    Mesh mesh = buildGridMesh(9, 7);
    const SimplifyStats stats = simplifySerial(mesh, flat, 0);
    // The best colour of a flat picture is its colour (solved in double, stored as float).
    for (float value : flat.pixels) CHECK(value == Approx(0.25f).margin(1e-6));
    CHECK(checkMesh(mesh) == "");
    CHECK(stats.vertices_after == 4);
    CHECK(stats.last_cost == 0.0);
}

TEST_CASE("greedy simplify: a plane costs nothing, a bump on it its error") {
    // A linear ramp is one plane in (x, y, value): every collapse lies on it and costs nothing,
    // down to the corners. A bump of 0.5 on it costs about 0.5² times its triangles' area.
    const uint32_t w = 8, h = 6, bump = 3 * w + 4;
    std::vector<float> values(w * h);
    for (uint32_t v = 0; v < w * h; ++v) values[v] = 0.05f * float(v % w) + 0.02f * float(v / w);
    Mesh plane = buildGridMesh(w, h);
    Image ramp = makeImage(w, h, 1, values);
    const SimplifyStats flat = simplifySerial(plane, ramp, 4);
    CHECK(flat.vertices_after == 4);
    CHECK(flat.last_cost < 1e-12);  // rounding only
    // The corners keep their values: the plane's colour where they stand (to float rounding).
    for (uint32_t corner : {0u, w - 1, (h - 1) * w, h * w - 1}) CHECK(ramp.pixels[corner] == Approx(values[corner]).margin(1e-6));
    values[bump] += 0.5f;
    Mesh bumpy = buildGridMesh(w, h);
    Image bumped = makeImage(w, h, 1, values);
    const SimplifyStats with_bump = simplifySerial(bumpy, bumped, 4);
    CHECK(checkMesh(bumpy) == "");
    CHECK(with_bump.last_cost > 0.1);
}

TEST_CASE("greedy simplify: a largest error stops the collapses that would exceed it") {
    const Image photo = photoPiece();
    const Mesh optimised = optimisedGridMesh(photo);
    uint32_t left[2];
    int i = 0;
    for (double levels : {2.0, 8.0}) {
        Mesh mesh = optimised;
        Image values = photo;
        const SimplifyStats stats = simplifySerial(mesh, values, 4, levels);
        CHECK(checkMesh(mesh) == "");
        CHECK(stats.vertices_after > 4);
        left[i++] = stats.vertices_after;
    }
    CHECK(left[1] < left[0]);
    // A flat picture costs nothing anywhere: down to the corners under any limit.
    Image flat = makeImage(9, 7, 1, std::vector<float>(63, 0.5f));
    Mesh mesh = buildGridMesh(9, 7);
    CHECK(simplifySerial(mesh, flat, 4, 0.5).vertices_after == 4);
}
