#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "cost.h"
#include "lawson.h"
#include "mesh.h"
#include "render.h"
#include "test_support.h"

using ddt::OutputSize;
using ddt::test::makeImage;

namespace ddt {
// For CHECK(size == OutputSize{...}) (found by argument-dependent lookup).
static bool operator==(OutputSize a, OutputSize b) { return a.width == b.width && a.height == b.height; }
static std::ostream& operator<<(std::ostream& out, OutputSize s) { return out << s.width << "x" << s.height; }
}  // namespace ddt

namespace {

// Sample coordinate of output index i in units of 1/(2·out): u = (i + 0.5)·in/out − 0.5,
// clamped into [0, in − 1], times 2·out (written here from render.h's description).
int64_t sampleUnits(uint32_t i, uint32_t in, uint32_t out) {
    const int64_t u = (2 * int64_t(i) + 1) * in - out;
    return std::clamp<int64_t>(u, 0, 2 * int64_t(out) * (in - 1));
}

// The sample coordinate of sampleUnits in 1/1024 pixels, rounded half up: on a mesh with
// explicit positions, samples are snapped to the positions' grid (render.h).
int64_t snappedUnits(uint32_t i, uint32_t in, uint32_t out) {
    return (sampleUnits(i, in, out) * 1024 + out) / (2 * int64_t(out));
}

// Counts the triangles containing each output sample under the tie rule of glsl/raster.h: a
// sample on a triangle's edge is moved by (dir_u·ε, dir_v·ε²), dir = +1 except −1 on the last
// row/column of the hull. Computed with a concrete ε: all coordinates are scaled by K² and
// the sample moved by (dir_u·K, dir_v), K = 2^16 > every coordinate difference, so the sign
// of each 128-bit edge function is that of the symbolic one. Coordinates: on the grid's mesh
// raster.h's exact units, on one with explicit positions 1/1024 pixels (snappedUnits).
std::vector<int> coverageCounts(const ddt::Mesh& mesh, OutputSize out) {
    const uint32_t w = mesh.width, h = mesh.height;
    const bool moved = !mesh.positions.empty();
    const __int128 k = __int128(1) << 16;
    REQUIRE((moved ? 1024 : 2 * int64_t(out.width)) * w < int64_t(k));
    REQUIRE((moved ? 1024 : 2 * int64_t(out.height)) * h < int64_t(k));
    std::vector<int> counts(size_t(out.width) * out.height, 0);
    for (const ddt::Triangle& t : ddt::listTriangles(mesh)) {
        const uint32_t ids[3] = {t.v0, t.v1, t.v2};
        __int128 px[3], py[3];
        for (int i = 0; i < 3; ++i) {
            px[i] = moved ? mesh.positions[ids[i]].x : 2 * int64_t(out.width) * (ids[i] % w);
            py[i] = moved ? mesh.positions[ids[i]].y : 2 * int64_t(out.height) * (ids[i] / w);
            px[i] *= k * k;
            py[i] *= k * k;
        }
        for (uint32_t y = 0; y < out.height; ++y) {
            const int64_t v = moved ? snappedUnits(y, h, out.height) : sampleUnits(y, h, out.height);
            const int dir_v = sampleUnits(y, h, out.height) == 2 * int64_t(out.height) * (h - 1) ? -1 : 1;
            for (uint32_t x = 0; x < out.width; ++x) {
                const int64_t u = moved ? snappedUnits(x, w, out.width) : sampleUnits(x, w, out.width);
                const int dir_u = sampleUnits(x, w, out.width) == 2 * int64_t(out.width) * (w - 1) ? -1 : 1;
                const __int128 su = __int128(u) * k * k + dir_u * k, sv = __int128(v) * k * k + dir_v;
                bool inside = true;
                for (int i = 0; i < 3 && inside; ++i) {
                    const int j = (i + 1) % 3;
                    inside = (px[j] - px[i]) * (sv - py[i]) - (py[j] - py[i]) * (su - px[i]) > 0;
                }
                counts[size_t(y) * out.width + x] += inside;
            }
        }
    }
    return counts;
}

std::vector<float> renderInto(const ddt::Mesh& mesh, const ddt::Image& image, OutputSize out, float fill) {
    std::vector<float> rows(size_t(out.width) * out.height * image.channels, fill);
    ddt::MeshRenderer(mesh, image).renderRows(out, 0, out.height, rows.data());
    return rows;
}

}  // namespace

TEST_CASE("render: output sizes are round(s*w) x round(s*h)") {
    // 5×3 input.
    CHECK(ddt::scaledOutputSize(5, 3, 1.0) == OutputSize{5, 3});
    CHECK(ddt::scaledOutputSize(5, 3, 2.0) == OutputSize{10, 6});
    CHECK(ddt::scaledOutputSize(5, 3, 2.5) == OutputSize{13, 8});  // 12.5 and 7.5 round half up
    CHECK(ddt::scaledOutputSize(5, 3, 3.0) == OutputSize{15, 9});
    CHECK(ddt::scaledOutputSize(5, 3, 8.0) == OutputSize{40, 24});
    CHECK(ddt::scaledOutputSize(7, 5, 2.5) == OutputSize{18, 13});  // 17.5, 12.5
    CHECK(ddt::scaledOutputSize(13, 9, 7.3) == OutputSize{95, 66});  // 94.9, 65.7
    CHECK(ddt::scaledOutputSize(512, 512, 8.0) == OutputSize{4096, 4096});
    // One side given, the other keeps the aspect: round(17·3/5) = round(10.2) = 10,
    // round(11·5/3) = round(18.33) = 18, round(1000·480/640) = 750, round(1001·640/480) =
    // round(1334.67) = 1335.
    CHECK(ddt::outputSizeForWidth(5, 3, 17) == OutputSize{17, 10});
    CHECK(ddt::outputSizeForHeight(5, 3, 11) == OutputSize{18, 11});
    CHECK(ddt::outputSizeForWidth(640, 480, 1000) == OutputSize{1000, 750});
    CHECK(ddt::outputSizeForHeight(640, 480, 1001) == OutputSize{1335, 1001});
}

TEST_CASE("render: checkOutputSize refuses shrinking and oversized outputs") {
    CHECK(ddt::checkOutputSize(5, 3, {5, 3}) == "");
    CHECK(ddt::checkOutputSize(5, 3, {40, 24}) == "");
    CHECK(ddt::checkOutputSize(5, 3, {4, 3}) != "");
    CHECK(ddt::checkOutputSize(5, 3, {5, 2}) != "");
    CHECK(ddt::checkOutputSize(5, 3, {100, 2}) != "");
    // The exact coverage arithmetic needs in_w·in_h·out_w·out_h < 2^60.
    CHECK(ddt::checkOutputSize(1u << 15, (1u << 15) - 1, {1u << 15, (1u << 15) - 1}) == "");  // just below
    CHECK(ddt::checkOutputSize(1u << 15, 1u << 15, {1u << 15, 1u << 15}) != "");
}

TEST_CASE("render: scale 1 reproduces the input exactly") {
    // Each output sample is a vertex: one barycentric weight is the whole, the others 0.
    std::mt19937 rng(2024);
    for (uint32_t channels : {1u, 2u, 3u, 4u}) {
        for (auto [w, h] : {std::pair{2u, 2u}, {5u, 3u}, {9u, 12u}}) {
            ddt::Image image = ddt::test::randomImage(rng, w, h, channels);
            INFO(w << "x" << h << ", " << channels << " channels");
            ddt::Mesh grid = ddt::buildGridMesh(w, h);
            CHECK(ddt::test::samePixels(ddt::renderImage(grid, image, {w, h}).pixels, image.pixels));
            ddt::Mesh optimized = grid;
            ddt::optimizeSerial(optimized, ddt::costFieldOf(image));
            CHECK(ddt::test::samePixels(ddt::renderImage(optimized, image, {w, h}).pixels, image.pixels));
            CHECK(ddt::test::samePixels(ddt::renderImage(ddt::test::scrambledGridMesh(w, h, rng), image, {w, h}).pixels, image.pixels));
        }
    }
}

TEST_CASE("render: every output pixel belongs to exactly one triangle and is written") {
    // The buffer starts as NaN: a pixel no triangle writes stays NaN. Coverage is counted
    // independently with the documented tie rule: exactly one triangle per sample, so no
    // pixel can be written twice (the renderer decides inside-ness with that rule).
    std::mt19937 rng(17);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    struct Case {
        uint32_t w, h, out_w, out_h;
    };
    const Case cases[] = {{2, 2, 2, 2},   {2, 2, 3, 3},    {2, 2, 7, 5},   {5, 3, 17, 11}, {5, 3, 13, 8},
                          {3, 7, 8, 19},  {13, 9, 95, 66}, {6, 4, 6, 29},  {4, 4, 32, 32}, {11, 5, 12, 6}};
    for (const Case& c : cases) {
        ddt::Image image = ddt::test::randomImage(rng, c.w, c.h, 3);
        for (int variant = 0; variant < 3; ++variant) {
            const ddt::Mesh mesh = variant == 0   ? ddt::buildGridMesh(c.w, c.h)
                                   : variant == 1 ? ddt::test::scrambledGridMesh(c.w, c.h, rng)
                                                  : ddt::test::movedMesh(c.w, c.h, rng);
            const OutputSize out{c.out_w, c.out_h};
            const char* const kinds[] = {"grid", "scrambled", "moved"};
            INFO(c.w << "x" << c.h << " -> " << c.out_w << "x" << c.out_h << " " << kinds[variant]);
            if (variant == 2) REQUIRE(ddt::checkMesh(mesh).empty());
            const std::vector<float> rows = renderInto(mesh, image, out, nan);
            CHECK(std::none_of(rows.begin(), rows.end(), [](float v) { return std::isnan(v); }));
            const std::vector<int> counts = coverageCounts(mesh, out);
            CHECK(std::all_of(counts.begin(), counts.end(), [](int n) { return n == 1; }));
        }
    }
}

TEST_CASE("render: rendering in bands equals rendering at once, bit for bit") {
    std::mt19937 rng(99);
    for (auto [w, h, s] : {std::tuple{5u, 3u, 2.5}, {13u, 9u, 7.3}, {8u, 8u, 3.0}, {2u, 6u, 4.0}}) {
        ddt::Image image = ddt::test::randomImage(rng, w, h, 4);
        for (const ddt::Mesh& mesh : {ddt::test::scrambledGridMesh(w, h, rng), ddt::test::movedMesh(w, h, rng)}) {
        const OutputSize out = ddt::scaledOutputSize(w, h, s);
        const std::vector<float> whole = renderInto(mesh, image, out, 0.0f);
        const ddt::MeshRenderer renderer(mesh, image);
        for (uint32_t band : {1u, 2u, 3u, 7u, out.height}) {
            std::vector<float> banded(whole.size(), std::numeric_limits<float>::quiet_NaN());
            const size_t row_floats = size_t(out.width) * image.channels;
            for (uint32_t y = 0; y < out.height; y += band)
                renderer.renderRows(out, y, std::min(y + band, out.height), banded.data() + y * row_floats);
            INFO(w << "x" << h << " s=" << s << " bands of " << band << (mesh.positions.empty() ? "" : ", moved"));
            CHECK(ddt::test::samePixels(banded, whole));
        }
        }
    }
}

TEST_CASE("render: a linear image renders to the exact linear function, at pixel centres or moved vertices") {
    // z = c + a·x + b·y per channel (dyadic values, exact in float), each vertex's value the
    // plane at its position: piecewise-linear interpolation reproduces a plane on any
    // triangulation, at the sample's position (raster.h's exact one on the grid's vertices, the
    // snapped one, 1/1024 pixel, on moved vertices). The weights are exact integer edge
    // functions divided once in double (~1e-16), and the output is a float (2^-24 relative,
    // < 6e-8 for values ≤ 1), so 1e-6 is a tolerance with margin.
    std::mt19937 rng(5);
    const double planes[3][3] = {{0.125, 1.0 / 64, 1.0 / 32}, {0.75, -1.0 / 32, 1.0 / 128}, {0.5, 0.0, -1.0 / 16}};
    for (auto [w, h, s] : {std::tuple{9u, 7u, 2.5}, {5u, 8u, 7.3}, {4u, 4u, 8.0}}) {
        for (bool moved : {false, true}) {
            const ddt::Mesh mesh = moved ? ddt::test::movedMesh(w, h, rng) : ddt::test::scrambledGridMesh(w, h, rng);
            REQUIRE(ddt::checkMesh(mesh).empty());
            std::vector<float> pixels;
            for (uint32_t v = 0; v < w * h; ++v) {
                const ddt::Position p = ddt::positionOf(mesh, v);
                for (const auto& plane : planes) pixels.push_back(float(plane[0] + plane[1] * p.x / 1024.0 + plane[2] * p.y / 1024.0));
            }
            const ddt::Image image = makeImage(w, h, 3, pixels);
            const OutputSize out = ddt::scaledOutputSize(w, h, s);
            const ddt::Image rendered = ddt::renderImage(mesh, image, out);
            auto at = [&](uint32_t i, uint32_t in, uint32_t size) {
                return moved ? snappedUnits(i, in, size) / 1024.0 : double(sampleUnits(i, in, size)) / (2.0 * size);
            };
            double worst = 0.0;
            for (uint32_t y = 0; y < out.height; ++y)
                for (uint32_t x = 0; x < out.width; ++x) {
                    const double u = at(x, w, out.width), v = at(y, h, out.height);
                    for (int k = 0; k < 3; ++k) {
                        const double expected = planes[k][0] + planes[k][1] * u + planes[k][2] * v;
                        worst = std::max(worst, std::abs(rendered.pixels[(size_t(y) * out.width + x) * 3 + k] - expected));
                    }
                }
            INFO(w << "x" << h << " s=" << s << (moved ? ", moved" : ", scrambled"));
            CHECK(worst < 1e-6);
        }
    }
}

TEST_CASE("render: the grid's mesh with its positions made explicit renders as the grid's, but for snapped samples") {
    // Explicit positions snap each sample to 1/1024 pixel: it moves by at most 1/2048 along
    // each axis. Values lie in [0, 1], so on the grid's unit triangles the surface changes by
    // at most 1 per pixel along each axis (a flipped mesh's thin triangles are steeper): the
    // two renders differ by at most 2/2048, plus float rounding.
    // At s = 1 and 2 the samples lie on the grid already (x/2 − 1/4): the renders are equal.
    std::mt19937 rng(7);
    for (auto [w, h, s] : {std::tuple{9u, 7u, 2.5}, {5u, 8u, 7.3}, {6u, 6u, 1.0}, {7u, 3u, 2.0}}) {
        const ddt::Image image = ddt::test::randomImage(rng, w, h, 3);
        ddt::Mesh mesh = ddt::buildGridMesh(w, h);
        const OutputSize out = ddt::scaledOutputSize(w, h, s);
        const std::vector<float> implicit = renderInto(mesh, image, out, 0.0f);
        ddt::makePositionsExplicit(mesh);
        const std::vector<float> explicit_positions = renderInto(mesh, image, out, 0.0f);
        double worst = 0.0;
        for (size_t i = 0; i < implicit.size(); ++i) worst = std::max(worst, double(std::abs(implicit[i] - explicit_positions[i])));
        INFO(w << "x" << h << " s=" << s);
        CHECK(worst <= 2.0 / 2048 + 1e-6);
        if (s == 1.0 || s == 2.0) CHECK(worst == 0.0);
    }
}

TEST_CASE("render: values stay within the input's range per channel") {
    // Barycentric weights are non-negative inside a triangle, so each output value is a
    // convex combination of three input values (and rounding to float is monotone).
    std::mt19937 rng(8);
    for (uint32_t channels : {1u, 3u, 4u}) {
        for (int round = 0; round < 4; ++round) {
            const uint32_t w = 3 + round * 3, h = 2 + round * 2;
            ddt::Image image = ddt::test::randomImage(rng, w, h, channels, round % 2 ? 4 : 0);
            ddt::Mesh mesh = ddt::test::scrambledGridMesh(w, h, rng);
            if (round == 3) {
                mesh = ddt::buildGridMesh(w, h);
                ddt::optimizeSerial(mesh, ddt::costFieldOf(image));
            }
            const ddt::Image rendered = ddt::renderImage(mesh, image, ddt::scaledOutputSize(w, h, 3.7));
            for (uint32_t k = 0; k < channels; ++k) {
                float lo = 1e30f, hi = -1e30f, out_lo = 1e30f, out_hi = -1e30f;
                for (size_t i = k; i < image.pixels.size(); i += channels) lo = std::min(lo, image.pixels[i]), hi = std::max(hi, image.pixels[i]);
                for (size_t i = k; i < rendered.pixels.size(); i += channels)
                    out_lo = std::min(out_lo, rendered.pixels[i]), out_hi = std::max(out_hi, rendered.pixels[i]);
                INFO(channels << " channels, round " << round << ", channel " << k);
                CHECK(out_lo >= lo);
                CHECK(out_hi <= hi);
            }
        }
    }
}

TEST_CASE("render: the output keeps the input's layout") {
    std::mt19937 rng(3);
    ddt::Image image = ddt::test::randomImage(rng, 5, 3, 2);
    image.sample_type = ddt::SampleType::UInt16;
    const ddt::Image rendered = ddt::renderImage(ddt::buildGridMesh(5, 3), image, {13, 8});
    CHECK(rendered.width == 13);
    CHECK(rendered.height == 8);
    CHECK(rendered.channels == 2);
    CHECK(rendered.sample_type == ddt::SampleType::UInt16);
    CHECK(rendered.pixels.size() == 13 * 8 * 2);
}
