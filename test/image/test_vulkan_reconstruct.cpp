// The consistent reconstruction on the Vulkan backend (glsl/image/reconstruct/), against core's
// reference (core/image/reconstruct.h) on the same mesh, against itself (runs, thread counts,
// tiles), and its guarantees: colour ≤ alpha, -s 1 returns the input. Every backend runs
// with the validation layer and synchronization validation; each test requires zero messages.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "reconstruct.h"
#include "render.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"
#include "tiled_upscale.h"
#include "vulkan_backend.h"

namespace {

using namespace ddt;

// Vulkan vs core on the same mesh. The two sum in different orders: both project onto the
// basis per triangle and then per vertex and edge, but core adds a vertex's triangles in
// their list order and the kernels walk its star; Dᵀ along x is a scatter in core and a
// gather here; the renderer's weights are fp64 on the host and fp32 on the device. Measured
// on these cases (13 images, every channel count and sample type, and the photo): at most
// 3.6e-7, a few ulps of values below 1. SART's steps divide by weights of order 1 and are
// clamped, so rounding is not amplified over three steps. 1e-5 leaves a 28× margin and stays
// below a 16-bit level (1.5e-5): a wrong tap, a missed triangle or a wrong half-edge moves
// samples by 1e-3 and more.
const float kCoreTolerance = 1e-5f;
// Tiled vs untiled (photo ×2, 64-pixel tiles, overlap 16): each crop is reconstructed on its
// own, its star walks start from other edge ids and SART's reach from the crop's border
// (about a pixel per step) fades inside the overlap. Measured: at most 3.0e-6.
const float kTileTolerance = 3e-5f;

VulkanBackend makeBackend() {
    VulkanOptions options;
    options.validation = true;
    return VulkanBackend(options);
}

// Random samples of `type`, colour premultiplied when there is alpha.
Image sampleImage(uint32_t width, uint32_t height, uint32_t channels, SampleType type, uint32_t seed) {
    std::mt19937 rng(seed);
    Image image = test::randomImage(rng, width, height, channels);
    image.sample_type = type;
    const float levels = type == SampleType::UInt8 ? 255.0f : type == SampleType::UInt16 ? 65535.0f : 0.0f;
    for (float& v : image.pixels)
        if (levels > 0) v = std::round(v * levels) / levels;
    if (image.hasAlpha())
        for (size_t p = 0; p < image.pixels.size(); p += channels)
            for (uint32_t k = 0; k + 1 < channels; ++k) image.pixels[p + k] *= image.pixels[p + channels - 1];
    return image;
}

DegradationModel modelFor(const Image& image, OutputSize out, AssumedKernel kernel = AssumedKernel::footprint) {
    return degradationFor(double(out.width) / image.width, double(out.height) / image.height, kernel);
}

// The Vulkan backend's consistent upscale of `image` (untiled); its optimised mesh in *mesh.
std::vector<float> vulkanUpscale(VulkanBackend& backend, const Image& image, OutputSize out, Mesh* mesh = nullptr,
                                 AssumedKernel kernel = AssumedKernel::footprint) {
    backend.prepare(image);
    backend.optimize();
    backend.reconstruct(modelFor(image, out, kernel));
    std::vector<float> rows(size_t(out.width) * out.height * image.channels);
    backend.renderRows(out, 0, out.height, rows.data());
    if (mesh) *mesh = backend.mesh();
    return rows;
}

struct Case {
    uint32_t channels;
    SampleType type;
    double scale_x, scale_y;
};

}  // namespace

TEST_CASE("vulkan reconstruct: equals core's reference on the same mesh", "[vulkan]") {
    VulkanBackend backend = makeBackend();
    const std::vector<Case> cases = {
        {1, SampleType::UInt8, 2.0, 2.0},   {2, SampleType::UInt8, 2.5, 2.5},   {3, SampleType::UInt8, 3.7, 3.7},
        {4, SampleType::UInt8, 2.0, 3.0},   {1, SampleType::UInt16, 2.5, 2.5}, {2, SampleType::UInt16, 3.7, 3.7},
        {3, SampleType::UInt16, 2.0, 3.0},  {4, SampleType::UInt16, 2.0, 2.0}, {1, SampleType::Float, 3.7, 3.7},
        {2, SampleType::Float, 2.0, 3.0},   {3, SampleType::Float, 2.0, 2.0},  {4, SampleType::Float, 2.5, 2.5},
        {3, SampleType::UInt8, 1.5, 4.0}};
    float largest = 0.0f;
    uint32_t seed = 1;
    for (const Case& c : cases) {
        const Image image = sampleImage(23, 17, c.channels, c.type, seed++);
        const OutputSize out{uint32_t(std::lround(c.scale_x * image.width)),
                             uint32_t(std::lround(c.scale_y * image.height))};
        INFO(c.channels << " channels, " << sampleTypeName(c.type) << ", " << out.width << "x" << out.height);
        Mesh mesh;
        const std::vector<float> device = vulkanUpscale(backend, image, out, &mesh);
        const Surface surface = reconstructSurface(mesh, image, modelFor(image, out));
        const Image reference = renderImage(mesh, surface.values, out, surface.bubbles.data());
        const float difference = test::compareSamples(device, reference.pixels).max_difference;
        CHECK(difference <= kCoreTolerance);
        largest = std::max(largest, difference);
    }
    // The photo: texture, soft and hard edges, a mesh with long triangles.
    const Image photo = test::photoCrop();
    const OutputSize out = scaledOutputSize(photo.width, photo.height, 2.5);
    Mesh mesh;
    const std::vector<float> device = vulkanUpscale(backend, photo, out, &mesh);
    const Surface surface = reconstructSurface(mesh, photo, modelFor(photo, out));
    const float difference = test::compareSamples(device, renderImage(mesh, surface.values, out, surface.bubbles.data()).pixels).max_difference;
    CHECK(difference <= kCoreTolerance);
    largest = std::max(largest, difference);
    WARN("largest Vulkan-core difference: " << largest);
    CHECK(backend.validationMessages() == 0);
}

TEST_CASE("vulkan reconstruct: equals core's reference under every assumed filter", "[vulkan]") {
    // The named filters' taps are wider than the footprint's and, for bicubic and lanczos3,
    // negative in their lobes; mixed's are two kernels' at once.
    VulkanBackend backend = makeBackend();
    const std::vector<Case> cases = {{3, SampleType::UInt8, 2.0, 2.0}, {1, SampleType::Float, 3.7, 2.5}};
    uint32_t seed = 40;
    for (AssumedKernel kernel : {AssumedKernel::box, AssumedKernel::bicubic, AssumedKernel::lanczos3, AssumedKernel::mixed})
        for (const Case& c : cases) {
            const Image image = sampleImage(23, 17, c.channels, c.type, seed++);
            const OutputSize out{uint32_t(std::lround(c.scale_x * image.width)),
                                 uint32_t(std::lround(c.scale_y * image.height))};
            INFO(assumedKernelName(kernel) << ", " << c.channels << " channels, " << out.width << "x" << out.height);
            Mesh mesh;
            const std::vector<float> device = vulkanUpscale(backend, image, out, &mesh, kernel);
            const Surface surface = reconstructSurface(mesh, image, modelFor(image, out, kernel));
            CHECK(test::compareSamples(device, renderImage(mesh, surface.values, out, surface.bubbles.data()).pixels).max_difference <= kCoreTolerance);
        }
    CHECK(backend.validationMessages() == 0);
}

TEST_CASE("vulkan reconstruct: the same output on every run", "[vulkan][heavy]") {
    VulkanBackend backend = makeBackend();
    const Image photo = test::photoCrop();
    const OutputSize out = scaledOutputSize(photo.width, photo.height, 2.5);
    const std::vector<float> first = vulkanUpscale(backend, photo, out);
    CHECK(test::samePixels(first, vulkanUpscale(backend, photo, out)));
    VulkanBackend other = makeBackend();
    CHECK(test::samePixels(first, vulkanUpscale(other, photo, out)));
    CHECK(backend.validationMessages() == 0);
    CHECK(other.validationMessages() == 0);
}

TEST_CASE("vulkan reconstruct: the same file whatever lavapipe's thread count", "[vulkan][heavy]") {
    TempFolder folder;
    const std::string input = test::testDataPath("crop32_astronaut.png");
    std::string previous;
    for (const char* threads : {"1", "2", "3"}) {
        const std::string output = (folder.path() / (std::string("out") + threads + ".png")).string();
        const Run run = runDdtup({input, "-s", "2.5", output, "--backend", "vulkan", "--reconstruct", "consistent"},
                                 {std::string("LP_NUM_THREADS=") + threads});
        REQUIRE(run.exit_code == 0);
        const std::string bytes = readFile(output);
        REQUIRE_FALSE(bytes.empty());
        if (!previous.empty()) CHECK(bytes == previous);
        previous = bytes;
    }
}

TEST_CASE("vulkan reconstruct: tiles agree with the untiled upscale", "[vulkan]") {
    VulkanBackend backend = makeBackend();
    const Image photo = test::photoCrop();
    const OutputSize out = scaledOutputSize(photo.width, photo.height, 2.0);
    auto upscale = [&](uint32_t tile) {
        TileOptions options;
        options.tile = tile;
        options.reconstruct = true;
        const size_t row_floats = size_t(out.width) * photo.channels;
        std::vector<float> result(row_floats * out.height);
        PackedImage packed(photo);
        upscaleRows(backend, packed, out, options, [&](OutputRows&& rows) {
            std::copy_n(rows.floats.get(), rows.rows() * row_floats, result.begin() + rows.y_begin * row_floats);
        });
        return result;
    };
    const std::vector<float> untiled = upscale(0);
    const test::Agreement agreement = test::compareSamples(untiled, upscale(64));
    WARN("tiled vs untiled: max difference " << agreement.max_difference << ", within one level "
                                             << agreement.within_one_level);
    CHECK(agreement.max_difference <= kTileTolerance);
    CHECK(backend.validationMessages() == 0);
}

TEST_CASE("vulkan reconstruct: premultiplied colour stays at most alpha", "[vulkan]") {
    VulkanBackend backend = makeBackend();
    for (uint32_t channels : {2u, 4u}) {
        const Image image = sampleImage(29, 21, channels, SampleType::Float, 40 + channels);
        const OutputSize out = scaledOutputSize(image.width, image.height, 3.7);
        const std::vector<float> rows = vulkanUpscale(backend, image, out);
        for (size_t p = 0; p < rows.size(); p += channels)
            for (uint32_t k = 0; k + 1 < channels; ++k) REQUIRE(rows[p + k] <= rows[p + channels - 1]);
    }
    CHECK(backend.validationMessages() == 0);
}

TEST_CASE("vulkan reconstruct: -s 1 returns the input exactly", "[vulkan]") {
    VulkanBackend backend = makeBackend();
    for (uint32_t channels : {1u, 3u, 4u}) {
        const Image image = sampleImage(19, 13, channels, SampleType::UInt8, 50 + channels);
        CHECK(test::samePixels(vulkanUpscale(backend, image, {image.width, image.height}), image.pixels));
    }
    CHECK(backend.validationMessages() == 0);
}
