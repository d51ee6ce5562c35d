#include "overshoot.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace bench {

namespace {

const int kThresholdLevels = 4;

// The first input index of the sample point of every output index along one axis.
std::vector<int64_t> sampleFloors(uint32_t out_side, uint32_t in_side) {
    const double scale = double(out_side) / double(in_side);
    std::vector<int64_t> floors(out_side);
    for (uint32_t i = 0; i < out_side; ++i) floors[i] = int64_t(std::floor((i + 0.5) / scale - 0.5));
    return floors;
}

struct Tally {
    uint64_t sum = 0, over = 0;

    void add(int value, int low, int high) {
        const int excess = std::max({0, value - high, low - value});
        sum += uint64_t(excess);
        over += excess > kThresholdLevels;
    }
    OvershootScores scores(uint64_t count) const {
        return {double(sum) / double(count), double(over) / double(count)};
    }
};

}  // namespace

Overshoot measureOvershoot(const ddt::ByteImage& input, const ddt::ByteImage& output) {
    assert(input.channels == output.channels);
    const uint32_t channels = input.channels;
    const std::vector<int64_t> fx = sampleFloors(output.width, input.width), fy = sampleFloors(output.height, input.height);
    auto value = [&](int64_t x, int64_t y, uint32_t c) {
        x = std::clamp<int64_t>(x, 0, input.width - 1);
        y = std::clamp<int64_t>(y, 0, input.height - 1);
        return int(input.values[(size_t(y) * input.width + size_t(x)) * channels + c]);
    };
    Tally wide, narrow;
    for (uint32_t y = 0; y < output.height; ++y)
        for (uint32_t x = 0; x < output.width; ++x)
            for (uint32_t c = 0; c < channels; ++c) {
                int wide_lo = 255, wide_hi = 0, narrow_lo = 255, narrow_hi = 0;
                for (int64_t dy = -1; dy <= 2; ++dy)
                    for (int64_t dx = -1; dx <= 2; ++dx) {
                        const int v = value(fx[x] + dx, fy[y] + dy, c);
                        wide_lo = std::min(wide_lo, v), wide_hi = std::max(wide_hi, v);
                        if (dx >= 0 && dx <= 1 && dy >= 0 && dy <= 1)
                            narrow_lo = std::min(narrow_lo, v), narrow_hi = std::max(narrow_hi, v);
                    }
                const int v = output.values[(size_t(y) * output.width + x) * channels + c];
                wide.add(v, wide_lo, wide_hi);
                narrow.add(v, narrow_lo, narrow_hi);
            }
    const uint64_t count = uint64_t(output.width) * output.height * channels;
    return {wide.scores(count), narrow.scores(count)};
}

}  // namespace bench
