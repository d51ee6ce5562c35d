// The quality metrics on images whose scores follow from the definitions by hand. Every
// expected value below is derived in its comment, never computed by core/metrics.
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <random>

#include "metrics.h"

namespace {

using ddt::ByteImage;

// A width × height image whose channel values are value(x, y, channel).
ByteImage makeImage(uint32_t width, uint32_t height, uint32_t channels,
                    const std::function<int(uint32_t, uint32_t, uint32_t)>& value) {
    ByteImage image{width, height, channels, {}};
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x)
            for (uint32_t c = 0; c < channels; ++c) image.values.push_back(uint8_t(value(x, y, c)));
    return image;
}

// +1 on even, −1 on odd coordinates.
int sign(uint32_t i) { return i % 2 == 0 ? 1 : -1; }

// A textured RGB image with every value in [20, 220]: room for offsets and noise.
ByteImage texturedRgb(uint32_t width, uint32_t height) {
    return makeImage(width, height, 3,
                     [](uint32_t x, uint32_t y, uint32_t c) { return 20 + int((x * 7 + y * 13 + c * 50) % 201); });
}

}  // namespace

TEST_CASE("metrics: identical images score perfectly") {
    const ByteImage image = texturedRgb(24, 20);
    const ddt::QualityScores s = ddt::compareImages(image, image);
    CHECK(s.mse == 0.0);
    CHECK(std::isinf(s.psnr));  // 10·log10(255² / 0)
    CHECK(std::isinf(s.snr));   // 10·log10(Σx² / 0)
    CHECK(s.correlation == Approx(1.0).epsilon(1e-12));
    CHECK(s.cross_correlation == Approx(1.0).epsilon(1e-12));
    // UIQI: σxy = σx² = σy² and μx = μy, so 4σ²μ² / (2σ² · 2μ²) = 1 in every window.
    CHECK(s.uiqi == Approx(1.0).epsilon(1e-12));
    // SSIM: (2μ² + C1)(2σ² + C2) / ((2μ² + C1)(2σ² + C2)) = 1 in every window.
    CHECK(s.ssim == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("metrics: a constant offset on a flat image") {
    // x = 100 everywhere, y = 110 everywhere, RGB; luma of (v, v, v) is v.
    const ByteImage x = makeImage(16, 12, 3, [](uint32_t, uint32_t, uint32_t) { return 100; });
    const ByteImage y = makeImage(16, 12, 3, [](uint32_t, uint32_t, uint32_t) { return 110; });
    // MSE = 10² = 100; PSNR = 10·log10(65025 / 100) = 10·log10(650.25) = 28.130804 dB.
    CHECK(ddt::meanSquaredError(x, y) == 100.0);
    CHECK(ddt::peakSignalToNoiseRatio(x, y) == Approx(28.130804).epsilon(1e-7));
    // SNR = 10·log10(Σ100² / Σ10²) = 10·log10(100) = 20 dB.
    CHECK(ddt::signalToNoiseRatio(x, y) == Approx(20.0).epsilon(1e-12));
    // Both windows flat: UIQI = 2·100·110 / (100² + 110²) = 22000 / 22100 = 0.99547511.
    CHECK(ddt::universalQualityIndex(x, y) == Approx(22000.0 / 22100.0).epsilon(1e-12));
    // SSIM: σ terms are C2 / C2 = 1; C1 = (0.01·255)² = 6.5025, so
    // (2·100·110 + 6.5025) / (100² + 110² + 6.5025) = 22006.5025 / 22106.5025 = 0.99547644.
    CHECK(ddt::structuralSimilarity(x, y) == Approx(22006.5025 / 22106.5025).epsilon(1e-12));
    // A flat image has no variance: Pearson's coefficient is undefined.
    CHECK(std::isnan(ddt::lumaCorrelation(x, y)));
    CHECK(std::isnan(ddt::crossCorrelation(x, y)));
}

TEST_CASE("metrics: a constant offset keeps the correlations at 1") {
    // Correlation removes the mean, so y = x + 10 (luma + 10 too, the weights sum to 1)
    // correlates perfectly with x, for luma and for the centred colour channels alike.
    const ByteImage x = texturedRgb(20, 20);
    ByteImage y = x;
    for (uint8_t& v : y.values) v = uint8_t(v + 10);
    CHECK(ddt::meanSquaredError(x, y) == 100.0);
    CHECK(ddt::lumaCorrelation(x, y) == Approx(1.0).epsilon(1e-12));
    CHECK(ddt::crossCorrelation(x, y) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("metrics: orthogonal stripe noise of known power") {
    // x = 100 ± 40 in alternate columns, y = x ± 30 in alternate rows (grey, 16×16). Over
    // the image, and over every 8×8 window, each parity is balanced and the two patterns
    // are orthogonal: μx = μy = 100, σx² = 1600, σn² = 900, σxy = σx² = 1600, σy² = 2500.
    const ByteImage x = makeImage(16, 16, 1, [](uint32_t col, uint32_t, uint32_t) { return 100 + 40 * sign(col); });
    const ByteImage y = makeImage(
        16, 16, 1, [](uint32_t col, uint32_t row, uint32_t) { return 100 + 40 * sign(col) + 30 * sign(row); });
    // MSE = 30² = 900; PSNR = 10·log10(65025 / 900) = 10·log10(72.25) = 18.588379 dB.
    CHECK(ddt::meanSquaredError(x, y) == 900.0);
    CHECK(ddt::peakSignalToNoiseRatio(x, y) == Approx(18.588379).epsilon(1e-7));
    // Mean x² = (140² + 60²) / 2 = 11600: SNR = 10·log10(11600 / 900) = 11.102155 dB.
    CHECK(ddt::signalToNoiseRatio(x, y) == Approx(11.102155).epsilon(1e-7));
    // Pearson = σxy / (σx σy) = 1600 / (40 · 50) = 0.8; grey, so cross-correlation agrees.
    CHECK(ddt::lumaCorrelation(x, y) == Approx(0.8).epsilon(1e-12));
    CHECK(ddt::crossCorrelation(x, y) == Approx(0.8).epsilon(1e-12));
    // UIQI = 4·1600·100·100 / ((1600 + 2500)(100² + 100²)) = 64e6 / 82e6 = 32/41.
    CHECK(ddt::universalQualityIndex(x, y) == Approx(32.0 / 41.0).epsilon(1e-12));
}

TEST_CASE("metrics: chroma noise that keeps luma moves cross-correlation only") {
    // x: grey stripes, every channel 100 ± 40 in alternate columns (σ² = 1600 per channel).
    // y = x + (15, −9, 7)·(±1 in alternate rows): 299·15 − 587·9 + 114·7 = 0, so luma is
    // unchanged and the luma correlation stays exactly 1. Per channel the noise is orthogonal
    // to the stripes: cov = 1600, var y_c = 1600 + n_c²; summed over channels,
    // cross-correlation = 3·1600 / √(3·1600 · (3·1600 + 15² + 9² + 7²)) = √(4800 / 5155)
    // = 0.96495. MSE = (225 + 81 + 49) / 3 = 118.333.
    const int noise[3] = {15, -9, 7};
    const ByteImage x = makeImage(16, 16, 3, [](uint32_t col, uint32_t, uint32_t) { return 100 + 40 * sign(col); });
    const ByteImage y = makeImage(
        16, 16, 3, [&](uint32_t col, uint32_t row, uint32_t c) { return 100 + 40 * sign(col) + noise[c] * sign(row); });
    CHECK(ddt::lumaCorrelation(x, y) == Approx(1.0).epsilon(1e-12));
    CHECK(ddt::crossCorrelation(x, y) == Approx(std::sqrt(4800.0 / 5155.0)).epsilon(1e-12));
    CHECK(ddt::meanSquaredError(x, y) == Approx(355.0 / 3.0).epsilon(1e-12));
}

TEST_CASE("metrics: checkerboard noise on a flat image") {
    // x = 128, y = 128 ± 20 as a checkerboard (grey, 24×24). The 11-tap Gaussian weights
    // g(i) = exp(−i²/4.5), i = −5..5, give S = Σ g(i)(−1)^i / Σ g(i) ≈ −1.39e−4, so in every
    // window μy = 128 ± 20·S² (within 4e−7 of 128) and σy² = 400·(1 − S⁴); x is flat, so
    // σxy = 0. SSIM = (2μxμy + C1)·C2 / ((μx² + μy² + C1)(σy² + C2)) → C2 / (400 + C2) with
    // C2 = (0.03·255)² = 58.5225: 58.5225 / 458.5225 = 0.12763278 (the S terms move it
    // by less than 1e−12).
    const ByteImage x = makeImage(24, 24, 1, [](uint32_t, uint32_t, uint32_t) { return 128; });
    const ByteImage y =
        makeImage(24, 24, 1, [](uint32_t col, uint32_t row, uint32_t) { return 128 + 20 * sign(col + row); });
    CHECK(ddt::structuralSimilarity(x, y) == Approx(58.5225 / 458.5225).epsilon(1e-9));
    // Every 8×8 window holds 32 of each sign: μy = 128 exactly, σy² = 400, σx² = σxy = 0,
    // so UIQI = 4·0·… / ((0 + 400)(2·128²)) = 0.
    CHECK(ddt::universalQualityIndex(x, y) == Approx(0.0).margin(1e-15));
    // MSE = 20² = 400.
    CHECK(ddt::meanSquaredError(x, y) == 400.0);
}

TEST_CASE("metrics: random signs of known amplitude give a known MSE") {
    // y = x ± 5 with random signs (seeded), no clipping since x is in [20, 220]: every
    // squared error is 25 whatever the signs, so MSE = 25 and
    // PSNR = 10·log10(65025 / 25) = 10·log10(2601) = 34.151404 dB.
    const ByteImage x = texturedRgb(32, 16);
    ByteImage y = x;
    std::mt19937 random(12345);
    for (uint8_t& v : y.values) v = uint8_t(v + (random() % 2 == 0 ? 5 : -5));
    CHECK(ddt::meanSquaredError(x, y) == 25.0);
    CHECK(ddt::peakSignalToNoiseRatio(x, y) == Approx(34.151404).epsilon(1e-7));
}

TEST_CASE("metrics: grey and RGB with equal channels score alike") {
    // Luma of (v, v, v) is v and the MSE averages equal channel errors: a grey image and
    // its three-channel copy give the same scores.
    auto grey_x = [](uint32_t x, uint32_t y, uint32_t) { return 30 + int((x * x + 3 * y) % 190); };
    auto grey_y = [](uint32_t x, uint32_t y, uint32_t) { return 35 + int((x * x + 3 * y + x * y) % 180); };
    const ddt::QualityScores grey = ddt::compareImages(makeImage(16, 16, 1, grey_x), makeImage(16, 16, 1, grey_y));
    const ddt::QualityScores rgb = ddt::compareImages(makeImage(16, 16, 3, grey_x), makeImage(16, 16, 3, grey_y));
    CHECK(rgb.mse == grey.mse);
    CHECK(rgb.snr == Approx(grey.snr).epsilon(1e-12));
    CHECK(rgb.correlation == Approx(grey.correlation).epsilon(1e-12));
    CHECK(rgb.cross_correlation == Approx(grey.cross_correlation).epsilon(1e-12));
    CHECK(rgb.uiqi == Approx(grey.uiqi).epsilon(1e-12));
    CHECK(rgb.ssim == Approx(grey.ssim).epsilon(1e-12));
}

TEST_CASE("metrics: images become 8-bit values by rounding, clamped, alpha dropped") {
    ddt::Image image;
    image.width = 2;
    image.height = 1;
    image.channels = 4;
    // 0.3/255 rounds down, 0.7/255 up; out-of-range values clamp; alpha is not kept.
    image.pixels = {0.3f / 255.0f, 0.7f / 255.0f, -0.2f, 0.5f, 1.3f, 200.0f / 255.0f, 1.0f, 1.0f};
    const ByteImage bytes = ddt::toBytes(image);
    CHECK(bytes.channels == 3);
    CHECK(bytes.values == std::vector<uint8_t>{0, 1, 0, 255, 200, 255});
}
