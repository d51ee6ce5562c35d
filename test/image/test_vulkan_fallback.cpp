// The convolution fallback on the Vulkan backend (glsl/image/fallback/) against core's
// ConvolutionFallback (core/image/convolution_fallback.h) blending core's rendering of the same
// surface: the grid's plain surface (no optimisation, so both backends hold the same mesh) of
// RGB, RGBA and grey inputs at ×2 and ×3.7, the consistent one, the bands of a huge
// magnification, and a tile's window. Every backend runs with the validation layer; each test
// requires zero messages.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "convolution_fallback.h"
#include "reconstruct.h"
#include "render.h"
#include "test_support.h"
#include "tiling.h"
#include "vulkan_backend.h"

namespace {

using namespace ddt;

// The device sums the 36 Lanczos3 taps, the Gaussian and the weights' bilinear lookup in
// float as core does, in the same order, but its taps' weights come from float sines (core's
// from double ones) and its compiler may fuse multiply-adds; the surfaces themselves differ
// by about 1e-7 (fp32 against fp64 barycentric weights). Measured on these tests: at most
// 4.2e-7. 1e-5 leaves room for a GPU's sine and stays below a 16-bit level (1.5e-5): a wrong
// tap or a weight from the wrong pixel moves samples by 1e-3 and more.
const float kCoreTolerance = 1e-5f;

VulkanBackend makeBackend() {
    VulkanOptions options;
    options.validation = true;
    return VulkanBackend(options);
}

// The photo piece with one more channel, alpha rising from 0.2 to 1 across it, colour premultiplied.
Image withAlpha(const Image& rgb) {
    std::vector<float> pixels;
    for (uint32_t y = 0; y < rgb.height; ++y)
        for (uint32_t x = 0; x < rgb.width; ++x) {
            const float alpha = 0.2f + 0.8f * float(x) / float(rgb.width - 1);
            for (uint32_t k = 0; k < 3; ++k) pixels.push_back(rgb.row(y)[size_t(x) * 3 + k] * alpha);
            pixels.push_back(alpha);
        }
    Image image = test::makeImage(rgb.width, rgb.height, 4, pixels);
    image.sample_type = rgb.sample_type;
    return image;
}

// The photo piece's grey: the mean of its channels, as 16-bit samples.
Image grey(const Image& rgb) {
    std::vector<float> pixels;
    for (size_t p = 0; p < rgb.pixels.size(); p += 3)
        pixels.push_back(std::round((rgb.pixels[p] + rgb.pixels[p + 1] + rgb.pixels[p + 2]) / 3.0f * 65535.0f) / 65535.0f);
    Image image = test::makeImage(rgb.width, rgb.height, 1, pixels);
    image.sample_type = SampleType::UInt16;
    return image;
}

// Core's rows of `window` over the surface `surface` of `mesh`: rendered, then blended.
std::vector<float> coreBlend(const Image& image, const Mesh& mesh, const RenderWindow& window,
                             const Surface* surface = nullptr, float grain_share = kGrainShare) {
    const MeshRenderer renderer = surface ? MeshRenderer(mesh, surface->values, surface->bubbles.data())
                                          : MeshRenderer(mesh, image);
    std::vector<float> rows(size_t(window.width()) * window.height() * image.channels);
    renderer.renderWindow(window, rows.data());
    ConvolutionFallback(image, grain_share).blend(window, rows.data());
    return rows;
}

std::vector<float> vulkanRows(VulkanBackend& backend, const RenderWindow& window, uint32_t channels) {
    std::vector<float> rows(size_t(window.width()) * window.height() * channels, std::nanf(""));
    backend.renderWindow(window, rows.data());
    return rows;
}

}  // namespace

TEST_CASE("vulkan fallback: blends the grid's plain surface as core's ConvolutionFallback", "[vulkan]") {
    Image rgb = test::photoPiece();
    rgb.sample_type = SampleType::UInt8;
    struct Case {
        const char* name;
        Image image;
    };
    const std::vector<Case> cases = {{"RGB", rgb}, {"RGBA", withAlpha(rgb)}, {"grey", grey(rgb)}};
    VulkanBackend backend = makeBackend();
    float largest = 0.0f;
    for (const Case& c : cases)
        for (double scale : {2.0, 3.7})
            for (float grain_share : {kGrainShare, 1.0f}) {  // the two shares grainShareFor gives
                const Image& image = c.image;
                const OutputSize out = scaledOutputSize(image.width, image.height, scale);
                const RenderWindow window = wholeRows(image.width, image.height, out, 0, out.height);
                INFO(c.name << " ×" << scale << ", grain share " << grain_share);
                backend.prepare(image);
                const std::vector<float> plain = vulkanRows(backend, window, image.channels);
                backend.addFallback(grain_share);
                const std::vector<float> device = vulkanRows(backend, window, image.channels);
                const std::vector<float> core =
                    coreBlend(image, buildGridMesh(image.width, image.height), window, nullptr, grain_share);
                const float difference = test::compareSamples(device, core).max_difference;
                CHECK(difference <= kCoreTolerance);
                largest = std::max(largest, difference);
                CHECK(test::compareSamples(device, plain).max_difference > 0.01f);  // the blend did move the surface
                if (image.hasAlpha())
                    for (size_t p = 0; p < device.size(); p += 4)
                        for (uint32_t k = 0; k < 3; ++k) REQUIRE(device[p + k] <= device[p + 3]);
                // prepare turns the fallback off again.
                backend.prepare(image);
                CHECK(test::compareSamples(vulkanRows(backend, window, image.channels), plain).max_difference == 0.0f);
            }
    WARN("largest Vulkan-core difference: " << largest);
    CHECK(backend.validationMessages() == 0);
}

TEST_CASE("vulkan fallback: blends the consistent surface as core's ConvolutionFallback", "[vulkan]") {
    // On the grid's mesh the two reconstructions agree to 3.6e-7 (test_vulkan_reconstruct.cpp).
    Image image = test::photoPiece();
    image.sample_type = SampleType::UInt8;
    const OutputSize out = scaledOutputSize(image.width, image.height, 3.7);
    const DegradationModel model =
        degradationFor(double(out.width) / image.width, double(out.height) / image.height, AssumedKernel::footprint);
    const RenderWindow window = wholeRows(image.width, image.height, out, 0, out.height);
    VulkanBackend backend = makeBackend();
    backend.prepare(image);
    backend.reconstruct(model);
    backend.addFallback(grainShareFor(AssumedKernel::footprint));
    const std::vector<float> device = vulkanRows(backend, window, image.channels);
    const Mesh mesh = buildGridMesh(image.width, image.height);
    const Surface surface = reconstructSurface(mesh, image, model);
    const float difference =
        test::compareSamples(device, coreBlend(image, mesh, window, &surface, grainShareFor(AssumedKernel::footprint)))
            .max_difference;
    WARN("consistent surface: Vulkan-core difference " << difference);
    CHECK(difference <= kCoreTolerance);
    CHECK(backend.validationMessages() == 0);
}

TEST_CASE("vulkan fallback: the bands of a huge magnification blend as core", "[vulkan]") {
    // At ×60 a band holds a few hundred rows (the render loop budget): the blend runs per band,
    // from its own first row. The optimised mesh, read back, is core's surface too.
    std::mt19937 rng(12);
    const Image image = test::randomImage(rng, 9, 7, 3);
    const OutputSize out = scaledOutputSize(image.width, image.height, 60.0);
    const RenderWindow window = wholeRows(image.width, image.height, out, 0, out.height);
    VulkanBackend backend = makeBackend();
    backend.prepare(image);
    backend.optimize();
    backend.addFallback(kGrainShare);
    const std::vector<float> device = vulkanRows(backend, window, image.channels);
    CHECK(test::compareSamples(device, coreBlend(image, backend.mesh(), window)).max_difference <= kCoreTolerance);
    CHECK(backend.validationMessages() == 0);
}

TEST_CASE("vulkan fallback: a tile's window blends as core and as the untiled image, bit for bit", "[vulkan]") {
    // A crop at an offset with an overlap of kFallbackReach + 1, as core's tile test: every
    // weight and tap a sample reads lies in the crop, so the tile's pixels are the whole image's.
    Image image = test::photoPiece();
    image.sample_type = SampleType::UInt8;
    const OutputSize out = scaledOutputSize(image.width, image.height, 3.7);
    VulkanBackend backend = makeBackend();
    backend.prepare(image);
    backend.addFallback(kGrainShare);
    const std::vector<float> whole =
        vulkanRows(backend, wholeRows(image.width, image.height, out, 0, out.height), image.channels);
    const uint32_t side = 32, y0 = 32;
    const std::vector<Tile> strip =
        planStrip(image.width, image.height, out, y0, stripEnd(image.height, y0, side), side, kFallbackReach + 1);
    REQUIRE(strip.size() >= 3);
    const Tile& tile = strip[1];  // cropped on all four sides
    REQUIRE(tile.crop.x0 > 0);
    REQUIRE(tile.crop.y0 > 0);
    REQUIRE(tile.crop.x1 < image.width);
    REQUIRE(tile.crop.y1 < image.height);
    const Image crop = cropOf(image, tile.crop);
    const RenderWindow window{image.width, image.height, out, tile.crop.x0, tile.crop.y0,
                              tile.output.x0, tile.output.x1, tile.output.y0, tile.output.y1};
    backend.prepare(crop);
    backend.addFallback(kGrainShare);
    const std::vector<float> device = vulkanRows(backend, window, image.channels);
    CHECK(test::compareSamples(device, coreBlend(crop, buildGridMesh(crop.width, crop.height), window)).max_difference <= kCoreTolerance);
    std::vector<float> untiled;
    const size_t row_floats = size_t(window.width()) * image.channels;
    for (uint32_t y = window.y_begin; y < window.y_end; ++y) {
        const float* row = whole.data() + (size_t(y) * out.width + window.x_begin) * image.channels;
        untiled.insert(untiled.end(), row, row + row_floats);
    }
    CHECK(test::samePixels(device, untiled));
    CHECK(backend.validationMessages() == 0);
}
