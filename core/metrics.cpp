#include "metrics.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace ddt {

namespace {

const double kInfinity = std::numeric_limits<double>::infinity();
const double kPeak = 255.0;

// SSIM constants of Wang et al. 2004: the 11×11 Gaussian window of σ = 1.5, K1, K2.
const int kSsimWindow = 11;
const double kSsimSigma = 1.5;
const double kSsimC1 = (0.01 * kPeak) * (0.01 * kPeak);
const double kSsimC2 = (0.03 * kPeak) * (0.03 * kPeak);

// UIQI window of Wang & Bovik 2002.
const int kUiqiWindow = 8;

void checkComparable(const ByteImage& a, const ByteImage& b) {
    assert(a.width == b.width && a.height == b.height && a.channels == b.channels);
    assert(a.values.size() == size_t(a.width) * a.height * a.channels);
    assert(b.values.size() == a.values.size());
    (void)a;
    (void)b;
}

// Luma scaled by 1000 is an integer (299 R + 587 G + 114 B), which keeps UIQI's flatness
// test exact; SSIM and correlation use the same values divided by 1000.
std::vector<int64_t> lumaTimes1000(const ByteImage& image) {
    std::vector<int64_t> luma(size_t(image.width) * image.height);
    const uint8_t* p = image.values.data();
    for (size_t i = 0; i < luma.size(); ++i, p += image.channels)
        luma[i] = image.channels == 1 ? 1000 * int64_t(p[0])
                                      : 299 * int64_t(p[0]) + 587 * int64_t(p[1]) + 114 * int64_t(p[2]);
    return luma;
}

std::vector<double> lumaOf(const ByteImage& image) {
    std::vector<int64_t> scaled = lumaTimes1000(image);
    std::vector<double> luma(scaled.size());
    for (size_t i = 0; i < luma.size(); ++i) luma[i] = double(scaled[i]) / 1000.0;
    return luma;
}

double pearson(const std::vector<double>& x, const std::vector<double>& y) {
    double mean_x = 0.0, mean_y = 0.0;
    for (size_t i = 0; i < x.size(); ++i) mean_x += x[i], mean_y += y[i];
    mean_x /= double(x.size());
    mean_y /= double(y.size());
    double xy = 0.0, xx = 0.0, yy = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
        const double dx = x[i] - mean_x, dy = y[i] - mean_y;
        xy += dx * dy, xx += dx * dx, yy += dy * dy;
    }
    return xx > 0.0 && yy > 0.0 ? xy / std::sqrt(xx * yy) : std::numeric_limits<double>::quiet_NaN();
}

// Sums of `plane` (width × height) over every window × window square lying fully inside,
// computed separably and exactly: (width − window + 1) × (height − window + 1) results.
std::vector<int64_t> boxSums(const std::vector<int64_t>& plane, uint32_t width, uint32_t height, uint32_t window) {
    const uint32_t out_w = width - window + 1, out_h = height - window + 1;
    std::vector<int64_t> rows(size_t(out_w) * height);
    for (uint32_t y = 0; y < height; ++y) {
        const int64_t* in = plane.data() + size_t(y) * width;
        int64_t sum = 0;
        for (uint32_t x = 0; x < window; ++x) sum += in[x];
        rows[size_t(y) * out_w] = sum;
        for (uint32_t x = 1; x < out_w; ++x) {
            sum += in[x + window - 1] - in[x - 1];
            rows[size_t(y) * out_w + x] = sum;
        }
    }
    std::vector<int64_t> sums(size_t(out_w) * out_h, 0);
    for (uint32_t y = 0; y < out_h; ++y)
        for (uint32_t k = 0; k < window; ++k)
            for (uint32_t x = 0; x < out_w; ++x) sums[size_t(y) * out_w + x] += rows[size_t(y + k) * out_w + x];
    return sums;
}

std::vector<double> gaussianTaps() {
    std::vector<double> taps(kSsimWindow);
    double total = 0.0;
    for (int i = 0; i < kSsimWindow; ++i) {
        const double d = i - kSsimWindow / 2;
        taps[i] = std::exp(-d * d / (2.0 * kSsimSigma * kSsimSigma));
        total += taps[i];
    }
    // The 2-D window is the outer product of these taps, so it sums to 1 as well.
    for (double& t : taps) t /= total;
    return taps;
}

// Gaussian-weighted means of `plane` over every 11×11 window lying fully inside.
std::vector<double> gaussianMeans(const std::vector<double>& plane, uint32_t width, uint32_t height,
                                  const std::vector<double>& taps) {
    const uint32_t out_w = width - kSsimWindow + 1, out_h = height - kSsimWindow + 1;
    std::vector<double> rows(size_t(out_w) * height);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < out_w; ++x) {
            double sum = 0.0;
            for (int k = 0; k < kSsimWindow; ++k) sum += taps[k] * plane[size_t(y) * width + x + k];
            rows[size_t(y) * out_w + x] = sum;
        }
    std::vector<double> means(size_t(out_w) * out_h, 0.0);
    for (uint32_t y = 0; y < out_h; ++y)
        for (int k = 0; k < kSsimWindow; ++k)
            for (uint32_t x = 0; x < out_w; ++x)
                means[size_t(y) * out_w + x] += taps[k] * rows[size_t(y + k) * out_w + x];
    return means;
}

std::vector<double> product(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> result(a.size());
    for (size_t i = 0; i < a.size(); ++i) result[i] = a[i] * b[i];
    return result;
}

std::vector<int64_t> product(const std::vector<int64_t>& a, const std::vector<int64_t>& b) {
    std::vector<int64_t> result(a.size());
    for (size_t i = 0; i < a.size(); ++i) result[i] = a[i] * b[i];
    return result;
}

}  // namespace

ByteImage toBytes(const Image& image) {
    ByteImage bytes;
    bytes.width = image.width;
    bytes.height = image.height;
    bytes.channels = image.channels >= 3 ? 3 : 1;
    const size_t pixels = size_t(image.width) * image.height;
    bytes.values.resize(pixels * bytes.channels);
    for (size_t i = 0; i < pixels; ++i)
        for (uint32_t c = 0; c < bytes.channels; ++c) {
            const float v = std::clamp(image.pixels[i * image.channels + c], 0.0f, 1.0f);
            bytes.values[i * bytes.channels + c] = uint8_t(std::lround(v * 255.0f));
        }
    return bytes;
}

double meanSquaredError(const ByteImage& original, const ByteImage& other) {
    checkComparable(original, other);
    uint64_t sum = 0;
    for (size_t i = 0; i < original.values.size(); ++i) {
        const int64_t d = int64_t(original.values[i]) - int64_t(other.values[i]);
        sum += uint64_t(d * d);
    }
    return double(sum) / double(original.values.size());
}

double peakSignalToNoiseRatio(const ByteImage& original, const ByteImage& other) {
    const double mse = meanSquaredError(original, other);
    return mse > 0.0 ? 10.0 * std::log10(kPeak * kPeak / mse) : kInfinity;
}

double signalToNoiseRatio(const ByteImage& original, const ByteImage& other) {
    checkComparable(original, other);
    uint64_t signal = 0, noise = 0;
    for (size_t i = 0; i < original.values.size(); ++i) {
        const int64_t x = original.values[i], d = x - int64_t(other.values[i]);
        signal += uint64_t(x * x);
        noise += uint64_t(d * d);
    }
    return noise > 0 ? 10.0 * std::log10(double(signal) / double(noise)) : kInfinity;
}

double lumaCorrelation(const ByteImage& original, const ByteImage& other) {
    checkComparable(original, other);
    return pearson(lumaOf(original), lumaOf(other));
}

double crossCorrelation(const ByteImage& original, const ByteImage& other) {
    checkComparable(original, other);
    const uint32_t c = original.channels;
    const size_t pixels = original.values.size() / c;
    std::vector<double> mean_x(c, 0.0), mean_y(c, 0.0);
    for (size_t i = 0; i < original.values.size(); ++i) {
        mean_x[i % c] += original.values[i];
        mean_y[i % c] += other.values[i];
    }
    for (uint32_t k = 0; k < c; ++k) mean_x[k] /= double(pixels), mean_y[k] /= double(pixels);
    double xy = 0.0, xx = 0.0, yy = 0.0;
    for (size_t i = 0; i < original.values.size(); ++i) {
        const double dx = original.values[i] - mean_x[i % c], dy = other.values[i] - mean_y[i % c];
        xy += dx * dy, xx += dx * dx, yy += dy * dy;
    }
    return xx > 0.0 && yy > 0.0 ? xy / std::sqrt(xx * yy) : std::numeric_limits<double>::quiet_NaN();
}

double universalQualityIndex(const ByteImage& original, const ByteImage& other) {
    checkComparable(original, other);
    assert(original.width >= kUiqiWindow && original.height >= kUiqiWindow);
    const uint32_t w = original.width, h = original.height;
    const std::vector<int64_t> x = lumaTimes1000(original), y = lumaTimes1000(other);
    const std::vector<int64_t> sx = boxSums(x, w, h, kUiqiWindow), sy = boxSums(y, w, h, kUiqiWindow);
    const std::vector<int64_t> sxx = boxSums(product(x, x), w, h, kUiqiWindow);
    const std::vector<int64_t> syy = boxSums(product(y, y), w, h, kUiqiWindow);
    const std::vector<int64_t> sxy = boxSums(product(x, y), w, h, kUiqiWindow);
    // With n values per window, n²·σ² = n·Σx² − (Σx)² and n²·μ² = (Σx)²; Q is a ratio of
    // terms of equal degree, so the common factors of n cancel. All integer and exact.
    const int64_t n = int64_t(kUiqiWindow) * kUiqiWindow;
    double total = 0.0;
    for (size_t i = 0; i < sx.size(); ++i) {
        const int64_t variances = n * sxx[i] - sx[i] * sx[i] + n * syy[i] - sy[i] * sy[i];
        const int64_t means = sx[i] * sx[i] + sy[i] * sy[i];
        const double mean_product = double(sx[i]) * double(sy[i]);
        if (variances == 0)
            total += means == 0 ? 1.0 : 2.0 * mean_product / double(means);
        else
            total += 4.0 * double(n * sxy[i] - sx[i] * sy[i]) * mean_product / (double(variances) * double(means));
    }
    return total / double(sx.size());
}

double structuralSimilarity(const ByteImage& original, const ByteImage& other) {
    checkComparable(original, other);
    assert(original.width >= kSsimWindow && original.height >= kSsimWindow);
    const uint32_t w = original.width, h = original.height;
    const std::vector<double> taps = gaussianTaps();
    const std::vector<double> x = lumaOf(original), y = lumaOf(other);
    const std::vector<double> mx = gaussianMeans(x, w, h, taps), my = gaussianMeans(y, w, h, taps);
    const std::vector<double> mxx = gaussianMeans(product(x, x), w, h, taps);
    const std::vector<double> myy = gaussianMeans(product(y, y), w, h, taps);
    const std::vector<double> mxy = gaussianMeans(product(x, y), w, h, taps);
    double total = 0.0;
    for (size_t i = 0; i < mx.size(); ++i) {
        const double var_x = mxx[i] - mx[i] * mx[i], var_y = myy[i] - my[i] * my[i];
        const double covariance = mxy[i] - mx[i] * my[i];
        total += (2.0 * mx[i] * my[i] + kSsimC1) * (2.0 * covariance + kSsimC2) /
                 ((mx[i] * mx[i] + my[i] * my[i] + kSsimC1) * (var_x + var_y + kSsimC2));
    }
    return total / double(mx.size());
}

QualityScores compareImages(const ByteImage& original, const ByteImage& other) {
    QualityScores scores;
    scores.mse = meanSquaredError(original, other);
    scores.psnr = peakSignalToNoiseRatio(original, other);
    scores.snr = signalToNoiseRatio(original, other);
    scores.correlation = lumaCorrelation(original, other);
    scores.cross_correlation = crossCorrelation(original, other);
    scores.uiqi = universalQualityIndex(original, other);
    scores.ssim = structuralSimilarity(original, other);
    return scores;
}

}  // namespace ddt
