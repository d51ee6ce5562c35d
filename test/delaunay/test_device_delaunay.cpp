// compute/delaunay/device_delaunay.h against the CPU reference: the same records, exactly.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "context.h"
#include "delaunay.h"
#include "delaunay/device_delaunay.h"
#include "mesh.h"
#include "test_support.h"

using namespace ddt;

namespace {

Position pixel(int32_t x, int32_t y) { return {x * kPositionOne, y * kPositionOne}; }

// The points in row-major order, each once: the form delaunayOfPoints takes.
std::vector<Position> rowMajor(std::vector<Position> points) {
    std::sort(points.begin(), points.end(), [](Position p, Position q) { return p.y != q.y ? p.y < q.y : p.x < q.x; });
    points.erase(std::unique(points.begin(), points.end()), points.end());
    return points;
}

// Every integer point at distance `radius` from `centre` (x² + y² = radius², by trying each x).
std::vector<Position> latticeCircle(Position centre, int64_t radius) {
    std::vector<Position> points;
    for (int64_t x = -radius; x <= radius; ++x) {
        const int64_t y_squared = radius * radius - x * x;
        int64_t y = int64_t(std::llround(std::sqrt(double(y_squared))));
        while (y * y > y_squared) --y;
        while ((y + 1) * (y + 1) <= y_squared) ++y;
        if (y * y != y_squared) continue;
        points.push_back({int32_t(centre.x + x), int32_t(centre.y + y)});
        points.push_back({int32_t(centre.x + x), int32_t(centre.y - y)});
    }
    return rowMajor(points);
}

// The device's mesh equals the reference's, record for record, and is Delaunay.
void requireSameAsReference(VulkanContext& context, uint32_t width, uint32_t height, const std::vector<Position>& points) {
    INFO(points.size() << " points in " << width << " x " << height);
    REQUIRE(delaunayInputProblem(points) == "");
    DeviceDelaunayStats stats;
    const Mesh device = deviceDelaunayOfPoints(context, width, height, points, &stats);
    const Mesh reference = delaunayOfPoints(width, height, points);
    INFO(stats.rounds << " rounds, " << stats.flips << " flips");
    // checkMesh's work grows with the frame's pixels; the largest frames rely on the equality.
    if (uint64_t(width) * height <= (1u << 24)) CHECK(checkMesh(device, MeshHull::convex) == "");
    CHECK(checkDelaunay(device) == "");
    CHECK(test::sameRecords(device, reference));
}

}  // namespace

TEST_CASE("device delaunay: random points give delaunayOfPoints' records", "[delaunay][vulkan]") {
    std::unique_ptr<VulkanContext> context = createContext({-1, true});
    for (const uint32_t seed : {1u, 2u, 3u}) {
        std::mt19937 rng(seed);
        for (const uint32_t count : {10u, 100u, 2000u}) {
            std::uniform_int_distribution<int32_t> coordinate(0, 999 * kPositionOne);
            std::vector<Position> points(count);
            for (Position& p : points) p = {coordinate(rng), coordinate(rng)};
            requireSameAsReference(*context, 1000, 1000, rowMajor(points));
        }
    }
    std::mt19937 rng(4);
    std::uniform_int_distribution<int32_t> coordinate(0, 999 * kPositionOne);
    std::vector<Position> points(20000);
    for (Position& p : points) p = {coordinate(rng), coordinate(rng)};
    requireSameAsReference(*context, 1000, 1000, rowMajor(points));
    CHECK(context->validation_messages == 0);
}

TEST_CASE("device delaunay: points over the largest frame, near the top of the range", "[delaunay][vulkan]") {
    std::unique_ptr<VulkanContext> context = createContext({-1, true});
    const int32_t top = int32_t(kMaxDelaunaySide - 1) * kPositionOne;  // 2^26 − 1024
    std::mt19937 rng(5);
    std::uniform_int_distribution<int32_t> anywhere(0, top), near_top(top - (1 << 14), top);
    std::vector<Position> points;
    for (int i = 0; i < 3000; ++i) points.push_back({anywhere(rng), anywhere(rng)});
    points.push_back({0, 0});
    points.push_back({top, top});
    requireSameAsReference(*context, kMaxDelaunaySide, kMaxDelaunaySide, rowMajor(points));
    // Far from the origin and close together: the lifts near 2^55, the minors tiny.
    std::vector<Position> corner;
    for (int i = 0; i < 3000; ++i) corner.push_back({near_top(rng), near_top(rng)});
    corner.push_back({0, top});
    requireSameAsReference(*context, kMaxDelaunaySide, kMaxDelaunaySide, rowMajor(corner));
    CHECK(context->validation_messages == 0);
}

TEST_CASE("device delaunay: the full pixel grid is buildGridMesh", "[delaunay][vulkan]") {
    std::unique_ptr<VulkanContext> context = createContext({-1, true});
    for (auto [width, height] : {std::pair{2u, 2u}, {3u, 5u}, {17u, 9u}, {64u, 48u}}) {
        INFO(width << " x " << height);
        std::vector<uint32_t> ids(width * height);
        for (uint32_t v = 0; v < ids.size(); ++v) ids[v] = v;
        const Mesh by_pixels = deviceDelaunayOfPixels(*context, width, height, ids);
        CHECK(test::sameRecords(by_pixels, buildGridMesh(width, height)));
        std::vector<Position> points;
        for (uint32_t v : ids) points.push_back(gridPosition(v, width));
        Mesh grid = buildGridMesh(width, height);
        makePositionsExplicit(grid);
        DeviceDelaunayStats stats;
        CHECK(test::sameRecords(deviceDelaunayOfPoints(*context, width, height, points, &stats), grid));
        // The sweep zips the first two rows with the grid's diagonals and cuts every later cell
        // by its other diagonal, a flip that shares no triangle with another: one round.
        CHECK(stats.rounds <= 1);
    }
    CHECK(context->validation_messages == 0);
}

TEST_CASE("device delaunay: known pixels give delaunayOfPixels' records", "[delaunay][vulkan]") {
    std::unique_ptr<VulkanContext> context = createContext({-1, true});
    std::mt19937 rng(6);
    for (const double density : {0.05, 0.5, 0.95}) {
        const uint32_t width = 80, height = 60;
        std::bernoulli_distribution keep(density);
        std::vector<uint32_t> ids;
        for (uint32_t v = 0; v < width * height; ++v)
            if (keep(rng)) ids.push_back(v);
        INFO("density " << density);
        CHECK(test::sameRecords(deviceDelaunayOfPixels(*context, width, height, ids),
                                delaunayOfPixels(width, height, ids)));
    }
    CHECK(context->validation_messages == 0);
}

TEST_CASE("device delaunay: cocircular points are cut by the symbolic tie-break", "[delaunay][vulkan]") {
    std::unique_ptr<VulkanContext> context = createContext({-1, true});
    SECTION("a random lattice: many cocircular quadruples") {
        std::mt19937 rng(7);
        std::uniform_int_distribution<int32_t> coordinate(0, 59);
        std::vector<Position> points;
        for (int i = 0; i < 2500; ++i) points.push_back(pixel(coordinate(rng), coordinate(rng)));
        requireSameAsReference(*context, 60, 60, rowMajor(points));
    }
    SECTION("the integer points of a circle spanning most of the range, then with its centre") {
        // 5^10 · 3 = 29 296 875 has many representations as a sum of two squares: 84 points.
        const Position centre = {1 << 25, 1 << 25};
        std::vector<Position> points = latticeCircle(centre, 29296875);
        REQUIRE(points.size() == 84);
        requireSameAsReference(*context, kMaxDelaunaySide, kMaxDelaunaySide, points);
        points.push_back(centre);
        requireSameAsReference(*context, kMaxDelaunaySide, kMaxDelaunaySide, rowMajor(points));
    }
    SECTION("that circle's points, each moved a unit: determinants near 0 against terms near 2^110") {
        std::vector<Position> points = latticeCircle({1 << 25, 1 << 25}, 29296875);
        std::mt19937 rng(9);
        std::uniform_int_distribution<int32_t> unit(-1, 1);
        for (Position& p : points) p = {p.x + unit(rng), p.y + unit(rng)};
        requireSameAsReference(*context, kMaxDelaunaySide, kMaxDelaunaySide, rowMajor(points));
    }
    SECTION("a small circle's points, each moved a unit: determinants of either sign near 0") {
        const Position centre = {50000, 50000};
        std::vector<Position> points = latticeCircle(centre, 5 * 5 * 5 * 5 * 5 * 13);
        REQUIRE(points.size() > 40);
        std::mt19937 rng(8);
        std::uniform_int_distribution<int32_t> unit(-1, 1);
        for (Position& p : points) p = {p.x + unit(rng), p.y + unit(rng)};
        requireSameAsReference(*context, 100, 100, rowMajor(points));
    }
    CHECK(context->validation_messages == 0);
}

TEST_CASE("device delaunay: collinear points on the hull and in long lines", "[delaunay][vulkan]") {
    std::unique_ptr<VulkanContext> context = createContext({-1, true});
    SECTION("a rectangle's border, every pixel, around a few inner points") {
        std::vector<Position> points;
        for (int32_t x = 0; x < 50; ++x) {
            points.push_back(pixel(x, 0));
            points.push_back(pixel(x, 29));
        }
        for (int32_t y = 1; y < 29; ++y) {
            points.push_back(pixel(0, y));
            points.push_back(pixel(49, y));
        }
        points.push_back({10 * kPositionOne + 300, 7 * kPositionOne + 11});
        points.push_back({33 * kPositionOne + 5, 20 * kPositionOne + 900});
        requireSameAsReference(*context, 50, 30, rowMajor(points));
    }
    SECTION("a first row of 500 collinear points, then one point below") {
        std::vector<Position> points;
        for (int32_t x = 0; x < 500; ++x) points.push_back({x * 100, 0});
        points.push_back({123, 7});
        requireSameAsReference(*context, 100, 100, points);
    }
    SECTION("two crossing lines: hull edges split many times, fans of high degree") {
        std::vector<Position> points;
        for (int32_t x = 0; x < 2000; ++x) {
            points.push_back({x * 512, 7 * kPositionOne});
            points.push_back({x * 512, x * 256});
        }
        requireSameAsReference(*context, 1001, 501, rowMajor(points));
    }
    SECTION("a diagonal line with points on both sides") {
        std::vector<Position> points;
        for (int32_t i = 0; i < 300; ++i) points.push_back({i * 1000, i * 1000});
        points.push_back({250000, 20000});
        points.push_back({20000, 250000});
        requireSameAsReference(*context, 300, 300, rowMajor(points));
    }
    CHECK(context->validation_messages == 0);
}
