// fillFromNearest against a brute-force search of every covered pixel.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "nearest_fill.h"

namespace {

using namespace ddt;

const float kUncovered = std::numeric_limits<float>::quiet_NaN();

// The covered pixel nearest to (x, y): least squared distance, then least column, then least row.
size_t bruteForceNearest(const std::vector<float>& pixels, uint32_t width, uint32_t height, uint32_t channels,
                         uint32_t x, uint32_t y) {
    size_t best = SIZE_MAX;
    int64_t best_distance = INT64_MAX;
    for (uint32_t qx = 0; qx < width; ++qx)
        for (uint32_t qy = 0; qy < height; ++qy) {
            if (std::isnan(pixels[(size_t(qy) * width + qx) * channels])) continue;
            const int64_t dx = int64_t(qx) - x, dy = int64_t(qy) - y, distance = dx * dx + dy * dy;
            if (distance < best_distance) {  // columns, then rows, come in increasing order
                best_distance = distance;
                best = size_t(qy) * width + qx;
            }
        }
    return best;
}

}  // namespace

TEST_CASE("nearest fill: every uncovered pixel copies the nearest covered one", "[delaunay]") {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 40; ++trial) {
        const uint32_t width = 1 + rng() % 40, height = 1 + rng() % 30, channels = 1 + rng() % 4;
        // From one covered pixel in a hundred to most of them, with ties common on small grids.
        const double covered_share = trial % 4 == 0 ? 0.01 : trial % 4 == 1 ? 0.1 : trial % 4 == 2 ? 0.5 : 0.9;
        std::bernoulli_distribution covered(covered_share);
        std::vector<float> pixels(size_t(width) * height * channels, kUncovered);
        for (size_t v = 0; v < size_t(width) * height; ++v)
            if (covered(rng))
                for (uint32_t k = 0; k < channels; ++k) pixels[v * channels + k] = float(v) + 0.25f * float(k);
        pixels[(rng() % (size_t(width) * height)) * channels] = 0.5f;  // at least one covered
        for (size_t v = 0; v < size_t(width) * height; ++v)
            if (!std::isnan(pixels[v * channels]))
                for (uint32_t k = 1; k < channels; ++k)
                    if (std::isnan(pixels[v * channels + k])) pixels[v * channels + k] = 0.0f;
        const std::vector<float> before = pixels;
        fillFromNearest(pixels.data(), width, height, channels);
        INFO("trial " << trial << ": " << width << "×" << height << "×" << channels);
        for (uint32_t y = 0; y < height; ++y)
            for (uint32_t x = 0; x < width; ++x) {
                const size_t v = size_t(y) * width + x;
                const size_t source = std::isnan(before[v * channels]) ? bruteForceNearest(before, width, height, channels, x, y) : v;
                for (uint32_t k = 0; k < channels; ++k) REQUIRE(pixels[v * channels + k] == before[source * channels + k]);
            }
    }
}

TEST_CASE("nearest fill: nothing changes without a covered pixel", "[delaunay]") {
    std::vector<float> pixels(12 * 3, kUncovered);
    fillFromNearest(pixels.data(), 4, 3, 3);
    for (float value : pixels) CHECK(std::isnan(value));
}

TEST_CASE("nearest fill: ties go to the smaller column, then the smaller row", "[delaunay]") {
    // Covered: A at (0, 1) and B at (2, 1), C at (1, 3); the pixel (1, 1) is 1 from A and B,
    // 2 from C: it takes A. (1, 2) is √2 from A and B and 1 from C: it takes C.
    //   . . .
    //   A ? B
    //   . ? .
    //   . C .
    const uint32_t width = 3, height = 4;
    std::vector<float> pixels(width * height, kUncovered);
    pixels[1 * width + 0] = 1.0f;
    pixels[1 * width + 2] = 2.0f;
    pixels[3 * width + 1] = 3.0f;
    fillFromNearest(pixels.data(), width, height, 1);
    CHECK(pixels[1 * width + 1] == 1.0f);
    CHECK(pixels[2 * width + 1] == 3.0f);
    CHECK(pixels[0 * width + 1] == 1.0f);  // (1, 0): √2 from A and B, 3 from C
    CHECK(pixels[2 * width + 2] == 2.0f);  // (2, 2): 1 from B
}
