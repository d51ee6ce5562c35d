#include "sample_patterns.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace bench {

namespace {

std::vector<uint32_t> randomPixels(double share, uint32_t width, uint32_t height, std::mt19937_64& rng) {
    const uint32_t n = width * height;
    std::vector<uint32_t> ids(n);
    std::iota(ids.begin(), ids.end(), 0u);
    // A partial Fisher–Yates shuffle: the first `count` ids are a uniform random subset.
    const uint32_t count = std::min(n, uint32_t(std::lround(share * n)));
    for (uint32_t i = 0; i < count; ++i) std::swap(ids[i], ids[std::uniform_int_distribution<uint32_t>(i, n - 1)(rng)]);
    ids.resize(count);
    return ids;
}

std::vector<uint32_t> pixelsOutsideBlobs(double share, uint32_t width, uint32_t height, std::mt19937_64& rng) {
    const uint32_t n = width * height;
    const double side = std::min(width, height);
    std::uniform_real_distribution<double> radius(0.02 * side, 0.06 * side), cx(0, width - 1), cy(0, height - 1);
    std::vector<bool> removed(n, false);
    uint32_t removed_count = 0;
    while (removed_count < share * n) {
        const double r = radius(rng), x0 = cx(rng), y0 = cy(rng);
        const uint32_t y_begin = uint32_t(std::max(0.0, std::ceil(y0 - r))), y_end = uint32_t(std::min(height - 1.0, y0 + r));
        const uint32_t x_begin = uint32_t(std::max(0.0, std::ceil(x0 - r))), x_end = uint32_t(std::min(width - 1.0, x0 + r));
        for (uint32_t y = y_begin; y <= y_end; ++y)
            for (uint32_t x = x_begin; x <= x_end; ++x) {
                const double dx = x - x0, dy = y - y0;
                if (dx * dx + dy * dy > r * r || removed[y * width + x]) continue;
                removed[y * width + x] = true;
                ++removed_count;
            }
    }
    std::vector<uint32_t> ids;
    for (uint32_t v = 0; v < n; ++v)
        if (!removed[v]) ids.push_back(v);
    return ids;
}

}  // namespace

std::vector<uint32_t> knownPixelsOf(const SamplePattern& pattern, uint32_t width, uint32_t height, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::vector<uint32_t> ids = pattern.blobs ? pixelsOutsideBlobs(pattern.share, width, height, rng)
                                              : randomPixels(pattern.share, width, height, rng);
    for (uint32_t corner : {0u, width - 1, (height - 1) * width, height * width - 1}) ids.push_back(corner);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    return ids;
}

}  // namespace bench
