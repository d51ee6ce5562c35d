// core/delaunay/point_mesh.h: from a point file's samples to a mesh and its vertex values.
#include <catch2/catch.hpp>

#include "delaunay.h"
#include "mesh.h"
#include "delaunay/point_mesh.h"
#include "user_error.h"

namespace {

using namespace ddt;

// Grey points (x, y, value).
PointSamples greyPoints(std::vector<std::array<double, 3>> list) {
    PointSamples points;
    points.channels = 1;
    points.sample_type = SampleType::Float;
    for (const auto& [x, y, v] : list) {
        points.x.push_back(x);
        points.y.push_back(y);
        points.values.push_back(float(v));
    }
    return points;
}

std::string problemOf(const PointSamples& points, Frame frame) {
    try {
        triangulatePoints(points, frame);
    } catch (const UserError& error) {
        return error.what();
    }
    return "";
}

}  // namespace

TEST_CASE("point mesh: the default frame is the smallest from 0 that holds every point", "[delaunay]") {
    const Frame frame = frameOfPoints(greyPoints({{0, 0, 0}, {9.25, 1, 0}, {3, 4, 0}}));
    CHECK(frame.width == 11);  // x up to 9.25 needs pixel centre 10
    CHECK(frame.height == 5);
    const Frame tiny = frameOfPoints(greyPoints({{0, 0, 0}, {0.5, 0, 0}, {0, 0.5, 0}}));
    CHECK(tiny.width == 2);
    CHECK(tiny.height == 2);
}

TEST_CASE("point mesh: points off the pixel centres keep their places, rounded to 1/1024 pixel", "[delaunay]") {
    // Given out of row-major order: the mesh's vertices come sorted, the values with them.
    const PointSamples points = greyPoints({{3.5, 2, 0.3}, {0, 0, 0.1}, {0.25, 1.9996, 0.2}, {3, 0, 0.4}});
    const SampledPoints sampled = triangulatePoints(points, {5, 3});
    REQUIRE(sampled.mesh.positions.size() == 4);
    CHECK(checkMesh(sampled.mesh, MeshHull::convex).empty());
    CHECK(checkDelaunay(sampled.mesh).empty());
    // Row-major: (0, 0), (3, 0), (0.25, 1.9996 → 2048/1024), (3.5, 2).
    CHECK(sampled.mesh.positions[0] == Position{0, 0});
    CHECK(sampled.mesh.positions[1] == Position{3 * 1024, 0});
    CHECK(sampled.mesh.positions[2] == Position{256, 2 * 1024});
    CHECK(sampled.mesh.positions[3] == Position{3584, 2 * 1024});
    CHECK(sampled.values.width == 4);
    CHECK(sampled.values.height == 1);
    CHECK(sampled.values.pixels == std::vector<float>{0.1f, 0.4f, 0.2f, 0.3f});
}

TEST_CASE("point mesh: points on pixel centres take the image's mesh and a frame-sized image", "[delaunay]") {
    const PointSamples points = greyPoints({{0, 0, 0.1}, {2, 0, 0.2}, {1, 1, 0.3}, {0, 2, 0.4}, {2, 2, 0.5}});
    const SampledPoints sampled = triangulatePoints(points, {3, 3});
    CHECK(sampled.mesh.positions.empty());
    CHECK(sampled.mesh.width == 3);
    CHECK(sampled.values.width == 3);
    CHECK(sampled.values.height == 3);
    CHECK(sampled.values.pixels == std::vector<float>{0.1f, 0, 0.2f, 0, 0.3f, 0, 0.4f, 0, 0.5f});
    CHECK(sampled.mesh.edgeCount() == 8);  // 4 hull edges, 4 spokes to the centre
    CHECK(checkDelaunay(sampled.mesh).empty());
}

TEST_CASE("point mesh: straight alpha becomes premultiplied, equal points merge", "[delaunay]") {
    PointSamples points;
    points.channels = 2;
    points.sample_type = SampleType::Float;
    points.x = {0, 1, 0, 0.5, 1};
    points.y = {0, 0, 1, 1, 0};
    points.values = {0.5f, 0.5f, 1, 1, 1, 0, 0.2f, 1, 1, 1};  // point 5 repeats point 2 exactly
    const SampledPoints sampled = triangulatePoints(points, {2, 2});
    REQUIRE(sampled.mesh.positions.size() == 4);
    // Row-major: (0,0) (1,0) (0,1) (0.5,1); grey × alpha.
    CHECK(sampled.values.pixels == std::vector<float>{0.25f, 0.5f, 1, 1, 0, 0, 0.2f, 1});
}

TEST_CASE("point mesh: bad point sets are refused with the points named", "[delaunay]") {
    CHECK_THAT(problemOf(greyPoints({{0, 0, 0}, {5, 0, 0}, {0, 1, 0}}), {5, 2}),
               Catch::Contains("point 2 at (5, 0) lies outside the 5×2 frame"));
    CHECK_THAT(problemOf(greyPoints({{0, 0, 0}, {1, 0, 0.5}, {0, 1, 0}, {1, 0.0001, 0.6}}), {2, 2}),
               Catch::Contains("points 2 and 4 lie at the same place") && Catch::Contains("different values"));
    CHECK_THAT(problemOf(greyPoints({{0, 0, 0}, {1, 1, 0}, {2, 2, 0}}), {3, 3}), Catch::Contains("collinear"));
    CHECK_THAT(problemOf(greyPoints({{0, 0, 0}, {1, 1, 0}, {0, 0, 0}}), {3, 3}), Catch::Contains("fewer than 3"));
}
