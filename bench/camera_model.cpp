#include "camera_model.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace bench {

namespace {

const double kBlurPerFactor = 0.4;  // σ in original pixels per unit of factor
const double kNoise = 1.0 / 255.0;

// Row i of the weights: original pixel k's share of low-resolution pixel i, whose centre lies
// at original coordinate (i + 0.5)·f − 0.5. Pixels past the border count for the nearest one.
struct AxisWeights {
    std::vector<int> first;                  // first original pixel of each row
    std::vector<std::vector<double>> weights;
};

AxisWeights axisWeights(uint32_t low, double factor) {
    const double sigma = kBlurPerFactor * factor;
    const int radius = int(std::ceil(3.0 * sigma));
    AxisWeights axis;
    for (uint32_t i = 0; i < low; ++i) {
        const double centre = (i + 0.5) * factor - 0.5;
        const int from = int(std::floor(centre)) - radius;
        std::vector<double> w;
        double total = 0.0;
        for (int k = from; k <= from + 2 * radius + 1; ++k) {
            const double d = (k - centre) / sigma;
            w.push_back(std::exp(-0.5 * d * d));
            total += w.back();
        }
        for (double& x : w) x /= total;
        axis.first.push_back(from);
        axis.weights.push_back(std::move(w));
    }
    return axis;
}

}  // namespace

ddt::Image cameraCapture(const ddt::Image& original, Magnification factor) {
    const uint32_t c = original.channels, w = original.width, h = original.height;
    const uint32_t lw = factor.lowSide(w), lh = factor.lowSide(h);
    const AxisWeights ax = axisWeights(lw, factor.value()), ay = axisWeights(lh, factor.value());
    auto clampTo = [](int k, uint32_t size) { return size_t(std::clamp(k, 0, int(size) - 1)); };
    // Along x, then along y.
    std::vector<double> rows(size_t(lw) * h * c, 0.0);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < lw; ++x)
            for (size_t j = 0; j < ax.weights[x].size(); ++j) {
                const float* in = original.pixels.data() + (size_t(y) * w + clampTo(ax.first[x] + int(j), w)) * c;
                for (uint32_t k = 0; k < c; ++k) rows[(size_t(y) * lw + x) * c + k] += ax.weights[x][j] * in[k];
            }
    ddt::Image low = original;
    low.width = lw;
    low.height = lh;
    low.pixels.assign(size_t(lw) * lh * c, 0.0f);
    std::mt19937 rng(1);
    std::normal_distribution<double> noise(0.0, kNoise);
    for (uint32_t y = 0; y < lh; ++y)
        for (uint32_t x = 0; x < lw; ++x)
            for (uint32_t k = 0; k < c; ++k) {
                double sum = 0.0;
                for (size_t j = 0; j < ay.weights[y].size(); ++j)
                    sum += ay.weights[y][j] * rows[(clampTo(ay.first[y] + int(j), h) * lw + x) * c + k];
                low.pixels[(size_t(y) * lw + x) * c + k] = float(sum + noise(rng));
            }
    return low;
}

}  // namespace bench
