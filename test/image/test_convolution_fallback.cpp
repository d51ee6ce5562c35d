// The convolution fallback (core/image/convolution_fallback.h): the surface's weight follows
// the input's local contrast and its orientation, against a double-precision eigenvalue
// formula written here; grain leans on the convolution more than a line does; where contrast
// is low, the output is the weighted mean of the surface and a Lanczos3 convolution written
// here from its textbook formula; tiles render the whole image's pixels bit for bit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
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

// The surface's weight at every pixel as convolution_fallback.h states it, in double: the
// Sobel gradient of the colours' mean, its tensor smoothed by the 7-tap Gaussian of σ = 1 in
// two dimensions at once, and the coherence from the tensor's eigenvalues.
std::vector<double> textbookWeights(const Image& image, double grain_share) {
    const int64_t w = image.width, h = image.height;
    auto mean = [&](int64_t x, int64_t y) {
        const float* p = image.row(uint32_t(std::clamp<int64_t>(y, 0, h - 1))) +
                         size_t(std::clamp<int64_t>(x, 0, w - 1)) * image.channels;
        double sum = 0.0;
        for (uint32_t k = 0; k < image.channels; ++k) sum += p[k];
        return sum / image.channels;
    };
    std::vector<std::array<double, 3>> tensor(size_t(w * h));
    for (int64_t y = 0; y < h; ++y)
        for (int64_t x = 0; x < w; ++x) {
            double gx = 0.0, gy = 0.0;
            for (int64_t d = -1; d <= 1; ++d) {
                const double side = d == 0 ? 2.0 : 1.0;
                gx += side * (mean(x + 1, y + d) - mean(x - 1, y + d)) / 8.0;
                gy += side * (mean(x + d, y + 1) - mean(x + d, y - 1)) / 8.0;
            }
            tensor[size_t(y * w + x)] = {gx * gx, gy * gy, gx * gy};
        }
    double total = 0.0;
    for (int k = -3; k <= 3; ++k) total += std::exp(-0.5 * k * k);
    std::vector<double> weights;
    for (int64_t y = 0; y < h; ++y)
        for (int64_t x = 0; x < w; ++x) {
            std::array<double, 3> j{};
            for (int64_t b = -3; b <= 3; ++b)
                for (int64_t a = -3; a <= 3; ++a) {
                    const double tap = std::exp(-0.5 * double(a * a)) * std::exp(-0.5 * double(b * b)) / (total * total);
                    const int64_t xx = std::clamp<int64_t>(x + a, 0, w - 1), yy = std::clamp<int64_t>(y + b, 0, h - 1);
                    const auto& t = tensor[size_t(yy * w + xx)];
                    for (int i = 0; i < 3; ++i) j[i] += tap * t[i];
                }
            const double half_sum = (j[0] + j[1]) / 2.0;
            const double radius = std::sqrt((j[0] - j[1]) * (j[0] - j[1]) / 4.0 + j[2] * j[2]);
            const double large = half_sum + radius, small = half_sum - radius;
            const double contrast = std::clamp((std::log10(j[0] + j[1]) - kLogFlat) / (kLogEdge - kLogFlat), 0.0, 1.0);
            const double coherence = large + small > 0.0 ? std::pow((large - small) / (large + small), 2.0) : 0.0;
            const double orientation = grain_share + (1.0 - grain_share) * coherence;
            weights.push_back(kWeightFlat + (kWeightEdge - kWeightFlat) * contrast * orientation);
        }
    return weights;
}

}  // namespace

TEST_CASE("fallback: the surface's weight follows the contrast and the coherence of the gradient, as stated") {
    // Random values with a contrast that rises across the image, so that every weight, from
    // flat to strong edges, and grain as well as the photo's lines are met.
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> pixels;
    for (uint32_t y = 0; y < 30; ++y)
        for (uint32_t x = 0; x < 40; ++x)
            for (uint32_t k = 0; k < 3; ++k) pixels.push_back(0.5f + (unit(rng) - 0.5f) * float(x * x) / 1600.0f);
    for (const Image& image : {test::makeImage(40, 30, 3, pixels), test::photoCrop()})
        for (float grain_share : {kGrainShare, 0.0f, 1.0f}) {
            CAPTURE(grain_share);
            const std::vector<float> weights = surfaceWeights(image, grain_share);
            const std::vector<double> expected = textbookWeights(image, grain_share);
            double worst = 0.0;
            for (size_t p = 0; p < weights.size(); ++p) worst = std::max(worst, std::abs(weights[p] - expected[p]));
            // Float sums of the tensor and float log10 against double: measured at most 2.4e-6.
            CHECK(worst < 1e-5);
        }
}

TEST_CASE("fallback: the grain's share is kGrainShare but under the footprint, where it is 1") {
    for (AssumedKernel kernel : {AssumedKernel::mixed, AssumedKernel::box, AssumedKernel::bicubic, AssumedKernel::lanczos3})
        CHECK(grainShareFor(kernel) == kGrainShare);
    CHECK(grainShareFor(AssumedKernel::footprint) == 1.0f);
}

TEST_CASE("fallback: grain leans on the convolution more than lines of the same contrast") {
    // Vertical lines (coherence 1) and white noise (no orientation) with the same strong contrast.
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> lines, noise;
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            lines.push_back(x % 4 < 2 ? 0.1f : 0.9f);
            noise.push_back(unit(rng) < 0.5f ? 0.1f : 0.9f);
        }
    for (float w : surfaceWeights(test::makeImage(32, 32, 1, lines), kGrainShare)) CHECK(w == kWeightEdge);
    // Noise's smoothed tensor keeps some orientation by chance (its coherence here averages
    // about 0.18: mean weight 0.51 against the grain's 0.42), so the bound sits a quarter of
    // the way from the grain's weight to an edge's; without the coherence term it is 0.9.
    const float grain = kWeightFlat + (kWeightEdge - kWeightFlat) * kGrainShare;
    double sum = 0.0;
    for (float w : surfaceWeights(test::makeImage(32, 32, 1, noise), kGrainShare)) sum += w;
    CHECK(sum / (32 * 32) < grain + 0.25 * (kWeightEdge - grain));
}

TEST_CASE("fallback: the surface's weight is kWeightFlat where the input is flat and kWeightEdge on a strong edge") {
    const Image step = stepImage(40, 12, 20);
    const std::vector<float> weights = surfaceWeights(step, kGrainShare);
    for (uint32_t y = 0; y < step.height; ++y) {
        CAPTURE(y);
        CHECK(weights[y * 40 + 2] == kWeightFlat);    // 18 pixels from the edge: no gradient reaches
        CHECK(weights[y * 40 + 37] == kWeightFlat);
        CHECK(weights[y * 40 + 19] == kWeightEdge);   // the step of 0.8: log10 T far above kLogEdge
        CHECK(weights[y * 40 + 20] == kWeightEdge);
        // Between, the weight falls off with the distance from the edge.
        for (uint32_t x = 20; x < 30; ++x) CHECK(weights[y * 40 + x + 1] <= weights[y * 40 + x]);
    }
    const std::vector<float> flat = surfaceWeights(test::makeImage(8, 8, 3, std::vector<float>(8 * 8 * 3, 0.4f)), kGrainShare);
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
    for (float w : surfaceWeights(image, kGrainShare)) REQUIRE(w == kWeightFlat);
    for (double scale : {2.0, 3.7}) {
        CAPTURE(scale);
        const OutputSize out = scaledOutputSize(image.width, image.height, scale);
        const Image surface = renderImage(buildGridMesh(image.width, image.height), image, out);
        std::vector<float> blended = surface.pixels;
        ConvolutionFallback(image, kGrainShare).blend(wholeRows(image.width, image.height, out, 0, out.height), blended.data());
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
    backend->addFallback(kGrainShare);
    std::vector<float> whole(size_t(out.width) * out.height * image.channels);
    backend->renderRows(out, 0, out.height, whole.data());
    // An overlap of kFallbackReach + 1: the crop holds every pixel the core's samples read.
    const uint32_t overlap = kFallbackReach + 1;
    std::vector<float> tiled(whole.size(), -1.0f);
    for (uint32_t y0 = 0; y0 < image.height; y0 = stripEnd(image.height, y0, 48))
        for (const Tile& tile : planStrip(image.width, image.height, out, y0, stripEnd(image.height, y0, 48), 48, overlap)) {
            const Image crop = cropOf(image, tile.crop);
            backend->prepare(crop);
            backend->addFallback(kGrainShare);
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
    backend->addFallback(kGrainShare);
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
