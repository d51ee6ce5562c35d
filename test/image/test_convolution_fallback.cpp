// The convolution fallback (core/image/convolution_fallback.h): the surface's weight follows
// the input's local contrast; where it is low, the output is the weighted mean of the surface
// and a Lanczos3 convolution written here from its textbook formula; tiles render the whole
// image's pixels bit for bit.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "backend.h"
#include "convolution_fallback.h"
#include "render.h"
#include "test_support.h"
#include "tiling.h"

namespace {

using namespace ddt;

// A vertical step from 0.1 to 0.9 at column `edge`, grey.
Image stepImage(uint32_t w, uint32_t h, uint32_t edge) {
    std::vector<float> pixels;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) pixels.push_back(x < edge ? 0.1f : 0.9f);
    return test::makeImage(w, h, 1, pixels);
}

double textbookLanczos3(double d) {
    if (std::abs(d) < 1e-12) return 1.0;
    if (std::abs(d) >= 3.0) return 0.0;
    return std::sin(M_PI * d) / (M_PI * d) * std::sin(M_PI * d / 3.0) / (M_PI * d / 3.0);
}

// Lanczos3 at output pixel (X, Y) of `out`, sampling the input at (X + 0.5)/s − 0.5 per axis,
// with edge pixels repeated beyond the border and the weights normalised to sum 1.
double lanczosAt(const Image& image, OutputSize out, uint32_t X, uint32_t Y, uint32_t channel) {
    const double u = (X + 0.5) * image.width / out.width - 0.5, v = (Y + 0.5) * image.height / out.height - 0.5;
    double sum = 0.0, total = 0.0;
    for (int64_t j = int64_t(std::ceil(v - 3.0)); j <= int64_t(std::floor(v + 3.0)); ++j)
        for (int64_t i = int64_t(std::ceil(u - 3.0)); i <= int64_t(std::floor(u + 3.0)); ++i) {
            const double weight = textbookLanczos3(u - double(i)) * textbookLanczos3(v - double(j));
            const int64_t x = std::clamp<int64_t>(i, 0, image.width - 1), y = std::clamp<int64_t>(j, 0, image.height - 1);
            sum += weight * image.pixels[(size_t(y) * image.width + size_t(x)) * image.channels + channel];
            total += weight;
        }
    return sum / total;
}

}  // namespace

TEST_CASE("fallback: the surface's weight is kWeightFlat where the input is flat and kWeightEdge on a strong edge") {
    const Image step = stepImage(40, 12, 20);
    const std::vector<float> weights = surfaceWeights(step);
    for (uint32_t y = 0; y < step.height; ++y) {
        CAPTURE(y);
        CHECK(weights[y * 40 + 2] == kWeightFlat);    // 18 pixels from the edge: no gradient reaches
        CHECK(weights[y * 40 + 37] == kWeightFlat);
        CHECK(weights[y * 40 + 19] == kWeightEdge);   // the step of 0.8: log10 T far above kLogEdge
        CHECK(weights[y * 40 + 20] == kWeightEdge);
        // Between, the weight falls off with the distance from the edge.
        for (uint32_t x = 20; x < 30; ++x) CHECK(weights[y * 40 + x + 1] <= weights[y * 40 + x]);
    }
    const std::vector<float> flat = surfaceWeights(test::makeImage(8, 8, 3, std::vector<float>(8 * 8 * 3, 0.4f)));
    for (float w : flat) CHECK(w == kWeightFlat);
}

TEST_CASE("fallback: where contrast is low the output is kWeightFlat · surface + (1 − kWeightFlat) · Lanczos3") {
    // Noise of ±0.002: the smoothed gradient energy stays below 10^kLogFlat, so every weight is
    // kWeightFlat and the convolution's share can be checked against the textbook formula.
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> noise(0.498f, 0.502f);
    std::vector<float> pixels(23 * 17 * 3);
    for (float& v : pixels) v = noise(rng);
    const Image image = test::makeImage(23, 17, 3, pixels);
    for (float w : surfaceWeights(image)) REQUIRE(w == kWeightFlat);
    for (double scale : {2.0, 3.7}) {
        CAPTURE(scale);
        const OutputSize out = scaledOutputSize(image.width, image.height, scale);
        const Image surface = renderImage(buildGridMesh(image.width, image.height), image, out);
        std::vector<float> blended = surface.pixels;
        ConvolutionFallback(image).blend(wholeRows(image.width, image.height, out, 0, out.height), blended.data());
        double worst = 0.0;
        for (uint32_t Y = 0; Y < out.height; ++Y)
            for (uint32_t X = 0; X < out.width; ++X)
                for (uint32_t k = 0; k < 3; ++k) {
                    const size_t i = (size_t(Y) * out.width + X) * 3 + k;
                    const double expected =
                        kWeightFlat * surface.pixels[i] + (1.0 - kWeightFlat) * lanczosAt(image, out, X, Y, k);
                    worst = std::max(worst, std::abs(expected - blended[i]));
                }
        // Float sums of 36 taps against double ones: a few float ulps of 0.5.
        CHECK(worst < 1e-6);
    }
}

TEST_CASE("fallback: a tile's crop renders exactly the whole image's blended pixels") {
    const Image image = test::photoCrop();
    const OutputSize out = scaledOutputSize(image.width, image.height, 2.3);
    std::unique_ptr<Backend> backend = makeCpuBackend();
    backend->prepare(image);
    backend->addFallback();
    std::vector<float> whole(size_t(out.width) * out.height * image.channels);
    backend->renderRows(out, 0, out.height, whole.data());
    // An overlap of kFallbackReach + 1: the crop holds every pixel the core's samples read.
    const uint32_t overlap = kFallbackReach + 1;
    std::vector<float> tiled(whole.size(), -1.0f);
    for (uint32_t y0 = 0; y0 < image.height; y0 = stripEnd(image.height, y0, 48))
        for (const Tile& tile : planStrip(image.width, image.height, out, y0, stripEnd(image.height, y0, 48), 48, overlap)) {
            const Image crop = cropOf(image, tile.crop);
            backend->prepare(crop);
            backend->addFallback();
            test::renderTileInto(*backend, image, out, tile, tiled);
        }
    CHECK(test::samePixels(tiled, whole));
}

TEST_CASE("fallback: the blend changes the surface's pixels and keeps them in [0, 1]") {
    const Image image = test::photoCrop();
    const OutputSize out = scaledOutputSize(image.width, image.height, 2.0);
    std::unique_ptr<Backend> backend = makeCpuBackend();
    backend->prepare(image);
    backend->optimize();
    std::vector<float> plain(size_t(out.width) * out.height * image.channels);
    backend->renderRows(out, 0, out.height, plain.data());
    backend->addFallback();
    std::vector<float> blended(plain.size());
    backend->renderRows(out, 0, out.height, blended.data());
    size_t changed = 0;
    for (size_t i = 0; i < plain.size(); ++i) {
        changed += blended[i] != plain[i];
        REQUIRE(blended[i] >= 0.0f);
        REQUIRE(blended[i] <= 1.0f);
    }
    CHECK(changed > plain.size() / 2);  // the convolution's share is at least 1 − kWeightEdge
}
