// `ddtup POINTS.csv|.ply [--frame WxH] OUT` through the real executable: a plane from scattered
// points on both backends, a full grid of points as the image itself, PLY input, refusals.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>

#include "image_file.h"
#include "plane_check.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

using namespace ddt;

double ramp(double x, double y) { return 0.1 + 0.02 * x + 0.03 * y; }

// plane.csv in `work`: the corners of a w × h frame and `count` points at random multiples of
// 1/1024 pixel (so that rounding to the position grid moves none of them), grey values of the
// plane, in [0, 1].
std::string writePlaneCsv(const TempFolder& work, uint32_t w, uint32_t h, uint32_t seed, int count) {
    std::ostringstream csv;
    csv << "x,y,v\n";
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> fx(0, int(w - 1) * 1024), fy(0, int(h - 1) * 1024);
    auto add = [&](double x, double y) { csv << x << ',' << y << ',' << ramp(x, y) << '\n'; };
    for (double x : {0.0, double(w - 1)})
        for (double y : {0.0, double(h - 1)}) add(x, y);
    for (int i = 0; i < count; ++i) add(fx(rng) / 1024.0, fy(rng) / 1024.0);
    const std::string points = work / "plane.csv";
    writeText(points, csv.str());
    return points;
}

}  // namespace

TEST_CASE("cli points: a plane comes back from scattered points on both backends", "[delaunay][vulkan]") {
    TempFolder work;
    const uint32_t w = 20, h = 15;
    const std::string points = writePlaneCsv(work, w, h, 5, 60);
    for (const std::string backend : {"cpu", "vulkan"}) {
        INFO(backend);
        const std::string output = work / (backend + ".tif");
        const Run run = runDdtup({points, "--frame", "20x15", "-s", "2", output, "--backend", backend, "-q"});
        REQUIRE(run.exit_code == 0);
        CHECK(run.err.empty());
        const Image out = readImage(output);
        REQUIRE(out.width == 2 * w);
        REQUIRE(out.height == 2 * h);
        CHECK(out.sample_type == SampleType::Float);  // values in [0, 1] with fractions: a float file
        // The renderer samples a mesh with explicit positions at the nearest 1/1024 pixel
        // (core/image/render.h), up to 1/2048 pixel off on each axis: at most (0.02 + 0.03) / 2048
        // = 2.4e-5 of the plane; 3e-5 leaves room for the float printing of the CSV's values
        // (6 significant digits, 5e-7 here) and float interpolation.
        CHECK(test::worstPlaneError(out, w, h, ramp) < 3e-5);
    }
}

TEST_CASE("cli points: --simplify keeps a fifth of the points, from which a plane comes back, on both backends",
          "[delaunay][vulkan]") {
    TempFolder work;
    const uint32_t w = 20, h = 15;
    const std::string points = writePlaneCsv(work, w, h, 6, 76);  // 80 points
    for (const std::string backend : {"cpu", "vulkan"}) {
        INFO(backend);
        const std::string output = work / (backend + ".tif"), mesh = work / (backend + ".ply");
        const Run run = runDdtup({points, "--frame", "20x15", "-s", "2", output, "--backend", backend, "--simplify", "0.2",
                                  "--mesh", mesh, "--stats"});
        REQUIRE(run.exit_code == 0);
        CHECK_THAT(run.out, Catch::Contains("80 -> 16  ("));
        // The mesh file has the kept vertices.
        CHECK_THAT(readFile(mesh), Catch::Contains("element vertex 16\n"));
        const Image out = readImage(output);
        REQUIRE(out.width == 2 * w);
        REQUIRE(out.height == 2 * h);
        // A plane's collapses cost nothing and keep each vertex on it, wherever it moves; the
        // tolerance is the one above (positions sampled at the nearest 1/1024 pixel).
        CHECK(test::worstPlaneError(out, w, h, ramp) < 3e-5);
    }
}

TEST_CASE("cli points: every pixel of an image as a point renders as the image, bit for bit", "[delaunay][vulkan]") {
    TempFolder work;
    const std::string input = test::testDataPath("crop32_astronaut.png");
    const Image image = readImage(input);
    REQUIRE(image.channels == 3);
    // 8-bit levels, in shuffled order: the file's order does not matter.
    std::vector<std::string> lines;
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            std::ostringstream line;
            line << x << ',' << y;
            for (uint32_t k = 0; k < 3; ++k) line << ',' << std::lround(image.pixels[(size_t(y) * image.width + x) * 3 + k] * 255);
            lines.push_back(line.str());
        }
    std::shuffle(lines.begin(), lines.end(), std::mt19937(1));
    std::string csv;
    for (const std::string& line : lines) csv += line + "\n";
    writeText(work / "all.csv", csv);
    for (const std::string backend : {"cpu", "vulkan"}) {
        INFO(backend);
        const Run plain = runDdtup({input, "-s", "3", work / "plain.png", "--reconstruct", "plain", "--backend", backend, "-q"});
        const Run points = runDdtup({work / "all.csv", "-s", "3", work / "points.png", "--backend", backend, "-q"});
        REQUIRE(plain.exit_code == 0);
        REQUIRE(points.exit_code == 0);
        CHECK(readImage(work / "plain.png").pixels == readImage(work / "points.png").pixels);
    }
}

TEST_CASE("cli points: a PLY of coloured vertices is read like a CSV", "[delaunay]") {
    TempFolder work;
    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
    writeText(work / "quad.ply", header + "0 0 0 255 0 0\n7.5 0 0 0 255 0\n0 3 0 0 0 255\n7.5 3 0 255 255 255\n");
    writeText(work / "quad.csv", "0,0,255,0,0\n7.5,0,0,255,0\n0,3,0,0,255\n7.5,3,255,255,255\n");
    for (const std::string name : {"quad.ply", "quad.csv"}) {
        const Run run = runDdtup({work / name, "-s", "2", work / (name + ".png"), "--backend", "cpu", "-q"});
        REQUIRE(run.exit_code == 0);
    }
    const Image ply = readImage(work / "quad.ply.png"), csv = readImage(work / "quad.csv.png");
    CHECK(ply.width == 18);  // frame 9 × 4: x up to 7.5 needs pixel centre 8
    CHECK(ply.height == 8);
    CHECK(ply.sample_type == SampleType::UInt8);
    CHECK(ply.pixels == csv.pixels);
    // The top-left output pixel samples input (−0.25, −0.25), clamped to the corner point: red.
    CHECK(ply.pixels[0] == 1.0f);
    CHECK(ply.pixels[1] == 0.0f);
}

TEST_CASE("cli points: bad point files and options are refused in one line", "[delaunay]") {
    TempFolder work;
    const std::string out = work / "out.png";
    auto file = [&](const std::string& name, const std::string& text) {
        writeText(work / name, text);
        return std::string(work / name);
    };
    const std::string outside = file("outside.csv", "0,0,0.5\n4,0,0.5\n0,3,0.5\n");
    requireOneLineError(runDdtup({outside, "--frame", "4x4", out}), 1, "outside.csv", "point 2 at (4, 0) lies outside the 4×4 frame");
    requireOneLineError(runDdtup({file("twice.csv", "0,0,0.5\n1,0,0.2\n0,1,0.5\n1,0,0.3\n"), out}), 1, "twice.csv",
                        "points 2 and 4 lie at the same place (1, 0");
    requireOneLineError(runDdtup({file("line.csv", "0,0,0.5\n1,1,0.5\n2,2,0.5\n"), out}), 1, "line.csv", "collinear");
    requireOneLineError(runDdtup({file("two.csv", "0,0,0.5\n1,1,0.5\n0,0,0.5\n"), out}), 1, "two.csv", "fewer than 3 points");
    requireOneLineError(runDdtup({file("nan.csv", "0,0,0.5\n1,1,nan\n0,1,0.5\n"), out}), 1, "nan.csv", "");
    requireOneLineError(runDdtup({file("huge.csv", "0,0,0.5\n70000,1,0.5\n0,1,0.5\n"), out}), 1, "huge.csv", "at most 65536");
    CHECK_FALSE(std::filesystem::exists(out));

    const std::string good = file("good.csv", "0,0,0.5\n3,0,0.5\n0,3,0.5\n");
    const Run merged = runDdtup({file("merge.csv", "0,0,0.5\n3,0,0.5\n0,3,0.5\n3,0,0.5\n"), out, "-q"});
    CHECK(merged.exit_code == 0);  // equal points with equal values are one point
    requireOneLineError(runDdtup({good, "--frame", "4", out}), 2, "--frame 4", "WIDTHxHEIGHT");
    requireOneLineError(runDdtup({good, "--frame", "1x4", out}), 2, "--frame 1x4", "at least 2");
    requireOneLineError(runDdtup({good, "--frame", "70000x4", out}), 2, "--frame", "65536");
    requireOneLineError(runDdtup({test::testDataPath("crop32_astronaut.png"), "--frame", "4x4", out}), 2, "--frame",
                        "point files");
    requireOneLineError(runDdtup({good, "--mask", work / "mask.png", out}), 2, "--mask", "point file");
    requireOneLineError(runDdtup({good, "-o", work / "dir"}), 2, "point file", "-f png");
    // Tiles take the points near each tile; a mesh file and a simplification take the whole
    // triangulation.
    requireOneLineError(runDdtup({good, out, "--tile", "64", "--mesh", work / "mesh.ply"}), 2, "point file", "--tile");
    CHECK_FALSE(std::filesystem::exists(work / "mesh.ply"));
    requireOneLineError(runDdtup({good, out, "--tile", "64", "--simplify", "0.5"}), 2, "point file", "--tile");
    requireOneLineError(runDdtup({good, out, "--simplify", "0.5", "--reconstruct", "consistent"}), 2, "--reconstruct",
                        "linear surface");
}
