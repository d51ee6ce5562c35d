// Tiling: the tile plan partitions input and output exactly; a crop's mesh renders the
// whole mesh's pixels where the meshes agree; tiled upscales agree with untiled ones; device
// out-of-memory errors (injected through DDTUP_TEST_DEVICE_MEMORY) lead to smaller tiles,
// never to a partial image.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <memory>
#include <random>
#include <string>

#include "backend.h"
#include "raster.h"
#include "test_support.h"
#include "tiled_upscale.h"
#include "tiling.h"
#include "vulkan_backend.h"

namespace {

using namespace ddt;

std::unique_ptr<Backend> makeBackendNamed(const std::string& name) {
    if (name == "cpu") return makeCpuBackend();
    VulkanOptions options;
    options.validation = true;
    return std::make_unique<VulkanBackend>(options);
}

// Every tile of a width × height input, strip by strip, as upscaleRows plans them when no
// retry shrinks the tiles.
std::vector<Tile> planTiles(uint32_t width, uint32_t height, OutputSize out, uint32_t side, uint32_t overlap) {
    std::vector<Tile> tiles;
    for (uint32_t y0 = 0; y0 < height; y0 = stripEnd(height, y0, side)) {
        const std::vector<Tile> strip = planStrip(width, height, out, y0, stripEnd(height, y0, side), side, overlap);
        tiles.insert(tiles.end(), strip.begin(), strip.end());
    }
    return tiles;
}

uint32_t validationMessages(Backend& backend) {
    auto* vulkan = dynamic_cast<VulkanBackend*>(&backend);
    return vulkan ? vulkan->validationMessages() : 0;
}

// Sets an environment variable for one scope.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const std::string& value) : name_(name) { setenv(name, value.c_str(), 1); }
    ~ScopedEnv() { unsetenv(name_); }

private:
    const char* name_;
};

// Hard edges in every direction, the case DDT's flips are for: a disc, a slanted step and
// thin diagonal lines, in RGB.
Image edgeImage(uint32_t w = 300, uint32_t h = 200) {
    std::vector<float> pixels;
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            const double dx = x - 0.55 * w, dy = y - 0.5 * h;
            const bool disc = dx * dx + dy * dy < 0.12 * w * h;
            const bool step = 3.0 * x + 7.0 * y > 2.5 * w;
            const bool line = (x + 2 * y) % 37 < 2;
            pixels.push_back(disc ? 0.9f : 0.1f);
            pixels.push_back(step ? 0.8f : 0.2f);
            pixels.push_back(line ? 1.0f : 0.3f * disc);
        }
    }
    return test::makeImage(w, h, 3, pixels);
}

std::vector<float> upscale(Backend& backend, const Image& image, OutputSize out, const TileOptions& options,
                           uint32_t* tiles = nullptr) {
    const size_t row_floats = size_t(out.width) * image.channels;
    std::vector<float> result(row_floats * out.height, -1.0f);
    uint32_t next_row = 0;
    PackedImage packed(image);
    upscaleRows(
        backend, packed, out, options,
        [&](OutputRows&& rows) {
            // Every row once, in order.
            REQUIRE(rows.y_begin == next_row);
            REQUIRE(rows.y_end > rows.y_begin);
            REQUIRE(rows.y_end <= out.height);
            std::copy_n(rows.floats.get(), rows.rows() * row_floats, result.begin() + rows.y_begin * row_floats);
            next_row = rows.y_end;
        },
        [&](const TileStep& step) {
            if (tiles) *tiles = step.tiles;
        });
    REQUIRE(next_row == out.height);
    return result;
}


TEST_CASE("tiling: cores partition the input and every output pixel belongs to exactly one tile") {
    const uint32_t sizes[][2] = {{2, 2}, {7, 5}, {97, 61}, {300, 200}, {64, 65}, {129, 3}};
    const double scales[] = {1.0, 1.37, 2.0, 3.9};
    for (auto [w, h] : sizes) {
        for (double scale : scales) {
            const OutputSize out = scaledOutputSize(w, h, scale);
            for (uint32_t side : {1u, 16u, 33u, 64u, 1000u}) {
                for (uint32_t overlap : {1u, 8u}) {
                    CAPTURE(w, h, scale, side, overlap);
                    std::vector<int> input_owner(size_t(w) * h, 0), output_owner(size_t(out.width) * out.height, 0);
                    for (const Tile& tile : planTiles(w, h, out, side, overlap)) {
                        REQUIRE(tile.core.width() >= 1);
                        REQUIRE(tile.core.width() <= side);
                        REQUIRE(tile.core.height() <= side);
                        CHECK(tile.crop.x0 == (tile.core.x0 > overlap ? tile.core.x0 - overlap : 0));
                        CHECK(tile.crop.y1 == std::min(h, tile.core.y1 + overlap));
                        for (uint32_t y = tile.core.y0; y < tile.core.y1; ++y)
                            for (uint32_t x = tile.core.x0; x < tile.core.x1; ++x) ++input_owner[size_t(y) * w + x];
                        for (uint32_t y = tile.output.y0; y < tile.output.y1; ++y) {
                            // The sample lies in the core (in sampleCoord's units), inside the crop's hull.
                            const int64_t v = sampleCoord(y, h, out.height);
                            CHECK(v >= vertexCoord(tile.core.y0, out.height));
                            CHECK(v < vertexCoord(tile.core.y1, out.height));
                            CHECK(v <= vertexCoord(tile.crop.y1 - 1, out.height));
                            for (uint32_t x = tile.output.x0; x < tile.output.x1; ++x)
                                ++output_owner[size_t(y) * out.width + x];
                        }
                        for (uint32_t x = tile.output.x0; x < tile.output.x1; ++x) {
                            const int64_t u = sampleCoord(x, w, out.width);
                            CHECK(u >= vertexCoord(tile.core.x0, out.width));
                            CHECK(u < vertexCoord(tile.core.x1, out.width));
                            CHECK(u <= vertexCoord(tile.crop.x1 - 1, out.width));
                        }
                    }
                    CHECK(std::count(input_owner.begin(), input_owner.end(), 1) == int64_t(input_owner.size()));
                    CHECK(std::count(output_owner.begin(), output_owner.end(), 1) == int64_t(output_owner.size()));
                }
            }
        }
    }
}

TEST_CASE("tiling: strips restart anywhere and never exceed the side") {
    for (uint32_t y0 : {0u, 1u, 50u, 199u})
        for (uint32_t side : {1u, 7u, 64u, 200u, 500u}) {
            const uint32_t end = stripEnd(200, y0, side);
            CHECK(end > y0);
            CHECK(end <= 200);
            CHECK(end - y0 <= side);
        }
}

// Where tiles run side by side, a strip's tile count becomes a multiple of the threads, so
// that its last round keeps them all busy, unless the tiles would fall below half the side.
TEST_CASE("tiling: a strip's columns are a multiple of the tiles at once, and cut near-equal") {
    CHECK(stripColumns(4224, 256, 1) == 17);
    CHECK(stripColumns(4224, 256, 2) == 18);
    CHECK(stripColumns(600, 256, 2) == 4);   // 3 cores of 200 → 4 of 150
    CHECK(stripColumns(512, 256, 2) == 2);   // already even
    CHECK(stripColumns(200, 256, 2) == 1);   // one tile: two would be below half the side
    CHECK(stripColumns(600, 256, 16) == 3);  // 16 cores of 37 would be below half the side
    CHECK(stripColumns(3000, 256, 4) == 12);
    for (uint32_t width : {1u, 2u, 7u, 97u, 300u, 601u, 4224u})
        for (uint32_t side : {1u, 16u, 64u, 256u})
            for (uint32_t at_once : {1u, 2u, 3u}) {
                CAPTURE(width, side, at_once);
                const uint32_t columns = stripColumns(width, side, at_once);
                const OutputSize out = scaledOutputSize(width, 10, 2.0);
                const std::vector<Tile> tiles = planStrip(width, 10, out, 0, 10, side, 4, columns);
                REQUIRE(tiles.size() == columns);
                CHECK(columns >= (width + side - 1) / side);
                uint32_t x = 0, narrowest = width, widest = 0;
                for (const Tile& tile : tiles) {
                    CHECK(tile.core.x0 == x);  // contiguous, left to right
                    x = tile.core.x1;
                    narrowest = std::min(narrowest, tile.core.width());
                    widest = std::max(widest, tile.core.width());
                }
                CHECK(x == width);
                CHECK(widest - narrowest <= 1);
                CHECK(widest <= side);
                // The count the side asks for cuts as planStrip did before counts were given:
                // each core near-equal over what is left, in as few parts as the side allows.
                if (at_once != 1) continue;
                uint32_t x0 = 0;
                for (const Tile& tile : tiles) {
                    const uint32_t left = width - x0, parts = (left + side - 1) / side;
                    CHECK(tile.core.x1 == x0 + (left + parts - 1) / parts);
                    x0 = tile.core.x1;
                }
            }
}

// On the unoptimised grid, a crop's mesh is the whole mesh restricted to the crop: the
// window it renders must equal the whole render bit for bit (same integers, same weights).
TEST_CASE("tiling: a crop's grid mesh renders exactly the whole grid's pixels", "[vulkan]") {
    const Image image = edgeImage(57, 43);
    const OutputSize out = scaledOutputSize(image.width, image.height, 2.3);
    for (const char* name : {"cpu", "vulkan"}) {
        CAPTURE(name);
        std::unique_ptr<Backend> backend = makeBackendNamed(name);
        backend->prepare(image);
        std::vector<float> whole(size_t(out.width) * out.height * image.channels);
        backend->renderRows(out, 0, out.height, whole.data());
        std::vector<float> tiled(whole.size(), -1.0f);
        for (const Tile& tile : planTiles(image.width, image.height, out, 16, 3)) {
            const Image crop = cropOf(image, tile.crop);
            backend->prepare(crop);
            test::renderTileInto(*backend, image, out, tile, tiled);
        }
        CHECK(test::samePixels(tiled, whole));
        CHECK(validationMessages(*backend) == 0);
    }
}

TEST_CASE("tiling: tiled and untiled upscales agree within 1/255 on 99.9 % of samples", "[vulkan]") {
    struct Case {
        const char* label;
        Image image;
    };
    std::mt19937 rng(6);
    const Case cases[] = {{"photo 300x200", test::photoCrop()},
                          {"edges 300x200", edgeImage()},
                          {"noise 300x200", test::randomImage(rng, 300, 200, 3)}};
    for (const char* name : {"cpu", "vulkan"}) {
        std::unique_ptr<Backend> backend = makeBackendNamed(name);
        for (const Case& c : cases) {
            const OutputSize out = scaledOutputSize(c.image.width, c.image.height, 2.0);
            const std::vector<float> untiled = upscale(*backend, c.image, out, {});
            for (uint32_t overlap : {4u, 8u, 16u, 32u}) {
                const uint32_t side = 64;
                uint32_t tiles = 0;
                const test::Agreement a =
                    test::compareSamples(upscale(*backend, c.image, out, {side, overlap}, &tiles), untiled);
                std::printf("tiling: %s, %s, x2, %u tiles of %u, overlap %2u: max difference %.4f (%.1f/255), "
                            "%.4f %% within 1/255\n",
                            name, c.label, tiles, side, overlap, a.max_difference, a.max_difference * 255.0f,
                            100.0 * a.within_one_level);
                CAPTURE(name, c.label, overlap, a.max_difference);
                CHECK(tiles == 20);
                if (overlap >= kDefaultOverlap) CHECK(a.within_one_level >= 0.999);
            }
        }
        CHECK(validationMessages(*backend) == 0);
    }
}

}  // namespace

namespace {

// The injected limits fail the untiled job in prepare (its 2.9 MB edge arrays) or, past
// prepare and optimize, in render (its 3.8 MB band of rendered rows); halving the tile side
// (300 → 150) gets crops whose buffers fit. The result is the untiled image.
TEST_CASE("tiling: an injected device out-of-memory error retries with smaller tiles, never a partial image", "[vulkan]") {
    const Image image = test::photoCrop();
    const OutputSize out = scaledOutputSize(image.width, image.height, 2.0);
    std::unique_ptr<Backend> backend = makeBackendNamed("vulkan");
    const std::vector<float> untiled = upscale(*backend, image, out, {});
    const std::vector<float> tiled_150 = upscale(*backend, image, out, {150});
    for (const char* limit_bytes : {"1048576", "3500000"}) {
        CAPTURE(limit_bytes);
        uint32_t tiles = 0;
        std::vector<float> retried;
        {
            // Test hook: allocations above the limit fail as VK_ERROR_OUT_OF_DEVICE_MEMORY.
            ScopedEnv limit("DDTUP_TEST_DEVICE_MEMORY", limit_bytes);
            retried = upscale(*backend, image, out, {}, &tiles);
        }
        CHECK(tiles == 4);  // tiles of 150: 2 columns, 2 strips
        const test::Agreement a = test::compareSamples(retried, untiled);
        std::printf("tiling: out-of-memory retry (limit %s bytes), %u tiles: max difference %.4f, "
                    "%.4f %% within 1/255\n",
                    limit_bytes, tiles, a.max_difference, 100.0 * a.within_one_level);
        CHECK(a.within_one_level >= 0.999);
        CHECK(test::samePixels(retried, tiled_150));
    }
    CHECK(validationMessages(*backend) == 0);
}

// A narrow, tall input streams strip by strip: the first strip's crop fits the limit, the
// second's (overlap on both sides) does not. The retry must not resend the first strip's rows.
TEST_CASE("tiling: a retry after rows were sent resends none of them", "[vulkan]") {
    const Image image = edgeImage(60, 300);
    const OutputSize out = scaledOutputSize(image.width, image.height, 1.5);
    const uint64_t first_strip = gridEdgeCount(60, 100 + kDefaultOverlap) * 16;
    const uint64_t second_strip = gridEdgeCount(60, 100 + 2 * kDefaultOverlap) * 16;
    std::unique_ptr<Backend> backend = makeBackendNamed("vulkan");
    const std::vector<float> untiled = upscale(*backend, image, out, {});
    uint32_t tiles = 0;
    std::vector<float> retried;
    {
        ScopedEnv limit("DDTUP_TEST_DEVICE_MEMORY", std::to_string((first_strip + second_strip) / 2));
        retried = upscale(*backend, image, out, {100}, &tiles);  // checks each row arrives once, in order
    }
    CHECK(tiles == 5);  // one strip of 100 rows, then four of 50
    CHECK(test::compareSamples(retried, untiled).within_one_level >= 0.999);
    CHECK(validationMessages(*backend) == 0);
}

TEST_CASE("tiling: when even the smallest tiles fail, one error, and the backend stays usable", "[vulkan]") {
    const Image image = edgeImage(100, 80);
    const OutputSize out = scaledOutputSize(image.width, image.height, 2.0);
    std::unique_ptr<Backend> backend = makeBackendNamed("vulkan");
    {
        ScopedEnv limit("DDTUP_TEST_DEVICE_MEMORY", "1000");
        CHECK_THROWS_WITH(upscale(*backend, image, out, {}),
                          Catch::StartsWith("not enough device memory even for 64×64 tiles (Vulkan: vkAllocateMemory "
                                            "failed with VK_ERROR_OUT_OF_DEVICE_MEMORY"));
    }
    const std::vector<float> after = upscale(*backend, image, out, {});
    const std::vector<float> fresh = upscale(*makeBackendNamed("vulkan"), image, out, {});
    CHECK(test::samePixels(after, fresh));
    CHECK(validationMessages(*backend) == 0);
}

// Upscales a side × side edge image by 1.5 with automatic tiling on the Vulkan device and
// checks that rows arrive once each, in order, finite and within the input's range, with the
// input's mean (no black or missing tiles).
void checkLargeUpscale(uint32_t side_px) {
    const Image image = edgeImage(side_px, side_px);
    const OutputSize out = scaledOutputSize(image.width, image.height, 1.5);
    VulkanOptions options;
    options.validation = true;
    VulkanBackend backend(options);
    const uint32_t side = automaticTileSide(backend, image.width, image.height, image.channels, kDefaultOverlap, false);
    CHECK(side > 0);
    const size_t row_floats = size_t(out.width) * image.channels;
    uint32_t next_row = 0, tiles = 0;
    size_t non_finite = 0;  // counted, not REQUIREd: one per sample
    double sum = 0.0;
    float low = 1.0f, high = 0.0f;
    const auto start = std::chrono::steady_clock::now();
    PackedImage packed(image);
    const OptimizeStats stats = upscaleRows(
        backend, packed, out, {},
        [&](OutputRows&& rows) {
            REQUIRE(rows.y_begin == next_row);
            next_row = rows.y_end;
            for (size_t i = 0; i < rows.rows() * row_floats; ++i) {
                const float value = rows.floats[i];
                non_finite += !std::isfinite(value);
                low = std::min(low, value);
                high = std::max(high, value);
                sum += value;
            }
        },
        [&](const TileStep& step) { tiles = step.tiles; });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("tiling: %s %ux%u -> %ux%u: %u tiles (automatic side %u), %.1f s (%llu flips, %u iterations, "
                "%.1f s optimising on the device)\n",
                backend.device().name.c_str(), image.width, image.height, out.width, out.height, tiles, side, seconds,
                (unsigned long long)stats.flips, stats.iterations, stats.device_ms * 1e-3);
    CHECK(next_row == out.height);
    CHECK(non_finite == 0);
    CHECK(tiles > 1);
    CHECK(low >= 0.0f);
    CHECK(high <= 1.0f);
    // The mean of the input, up to the interpolation at edges.
    double input_sum = 0.0;
    for (float v : image.pixels) input_sum += v;
    CHECK(sum / (double(row_floats) * out.height) == Approx(input_sum / image.pixels.size()).epsilon(0.01));
    CHECK(backend.validationMessages() == 0);
}

// lavapipe's 2 GiB heap holds about 2900² pixels of DDT's arrays: a 4096² input (4.1 GB
// untiled) must be tiled automatically. About 50 s on lavapipe with two threads.
TEST_CASE("tiling: a 4096x4096 input upscales on lavapipe in automatic tiles", "[heavy][vulkan]") { checkLargeUpscale(4096); }

// 8192²: beyond lavapipe's texel-buffer elements and largest allocation too. Minutes: run by hand.
TEST_CASE("tiling: an 8192x8192 input upscales on lavapipe in automatic tiles", "[.][large]") {
    checkLargeUpscale(8192);
}

}  // namespace
