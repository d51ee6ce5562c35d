#include "degradation.h"

#include <algorithm>

#include "channel_count.h"
#include "parallel.h"
#include "pixel_vector.h"

namespace ddt {

namespace {

// Rows per task: a row is thousands of samples.
const size_t kGrain = 8;

// The supersample t steps from the centre sample of pixel i, clamped into [0, size).
uint32_t centreSample(uint32_t i, int t, uint32_t size) {
    return uint32_t(std::clamp(int(i * kSupersampling + kSupersampling / 2) + t, 0, int(size) - 1));
}

// D along one axis of `pixels` pixels: pixel i takes taps[t + r] · supersample centre(i) + t,
// for t in [−r, r] in order.
AxisTaps applyTaps(uint32_t pixels, const std::vector<float>& taps) {
    const int r = int(taps.size() / 2);
    AxisTaps result;
    result.first.push_back(0);
    for (uint32_t i = 0; i < pixels; ++i) {
        for (int t = -r; t <= r; ++t) {
            result.index.push_back(centreSample(i, t, pixels * kSupersampling));
            result.weight.push_back(taps[t + r]);
        }
        result.first.push_back(uint32_t(result.index.size()));
    }
    return result;
}

// Dᵀ along the same axis: each supersample gathers the taps of applyTaps that land on it, in
// the order pixel by pixel, tap by tap (the order a scatter of D's taps would add them in).
AxisTaps transposeTaps(const AxisTaps& apply, uint32_t supersamples) {
    AxisTaps result;
    result.first.assign(supersamples + 1, 0);
    for (uint32_t s : apply.index) ++result.first[s + 1];
    for (uint32_t s = 0; s < supersamples; ++s) result.first[s + 1] += result.first[s];
    result.index.resize(apply.index.size());
    result.weight.resize(apply.index.size());
    std::vector<uint32_t> next(result.first.begin(), result.first.end() - 1);
    for (uint32_t i = 0; i < apply.outputs(); ++i)
        for (uint32_t j = apply.first[i]; j < apply.first[i + 1]; ++j) {
            const uint32_t slot = next[apply.index[j]]++;
            result.index[slot] = i;
            result.weight[slot] = apply.weight[j];
        }
    return result;
}

// Along y: output row o of `out` gathers whole rows of `in` (row_floats floats each), a block
// of the row at a time so that the sum stays in the L1 cache while its terms stream in.
void gatherRows(const AxisTaps& taps, const float* in, float* out, size_t row_floats) {
    const size_t kBlock = 1024;  // floats
    parallelFor(taps.outputs(), kGrain, [&](size_t begin, size_t end) {
        for (size_t o = begin; o < end; ++o) {
            const uint32_t first = taps.first[o], last = taps.first[o + 1];
            for (size_t block = 0; block < row_floats; block += kBlock) {
                float* row = out + o * row_floats + block;
                const size_t n = std::min(kBlock, row_floats - block);
                if (first == last) {
                    std::fill_n(row, n, 0.0f);
                    continue;
                }
                // 0 + the first term, as a sum from 0 has it (−0 becomes +0).
                const float* source = in + taps.index[first] * row_floats + block;
                const float g = taps.weight[first];
                for (size_t i = 0; i < n; ++i) row[i] = 0.0f + g * source[i];
                for (uint32_t j = first + 1; j < last; ++j) {
                    const float* source = in + taps.index[j] * row_floats + block;
                    const float g = taps.weight[j];
                    for (size_t i = 0; i < n; ++i) row[i] += g * source[i];
                }
            }
        }
    });
}

// Along x, in each of `rows` rows: output pixel o gathers pixels of the input row.
void gatherColumns(const AxisTaps& taps, uint32_t channels, const float* in, uint32_t in_pixels, float* out,
                   uint32_t rows) {
    withChannelCount(channels, [&](auto channel_count) {
        constexpr uint32_t c = decltype(channel_count)::value;
        const uint32_t out_pixels = taps.outputs();
        parallelFor(rows, kGrain, [&](size_t begin, size_t end) {
            for (size_t y = begin; y < end; ++y) {
                const float* source = in + y * in_pixels * c;
                float* row = out + y * out_pixels * c;
                for (uint32_t o = 0; o < out_pixels; ++o) {
                    PixelVector<c> sum = {};
                    for (uint32_t j = taps.first[o]; j < taps.first[o + 1]; ++j)
                        sum += taps.weight[j] * loadPixel<c>(source + size_t(taps.index[j]) * c);
                    storePixel<c>(row + o * c, sum);
                }
            }
        });
    });
}

}  // namespace

Degradation::Degradation(uint32_t width, uint32_t height, uint32_t channels, const DegradationModel& model)
    : w_(width), h_(height), c_(channels), sub_w_(width * kSupersampling), sub_h_(height * kSupersampling),
      apply_x_(applyTaps(width, degradationTaps(model.sigma_x))), apply_y_(applyTaps(height, degradationTaps(model.sigma_y))),
      transpose_x_(transposeTaps(apply_x_, sub_w_)), transpose_y_(transposeTaps(apply_y_, sub_h_)) {}

void Degradation::apply(const std::vector<float>& sub, std::vector<float>& degraded) {
    between_.resize(size_t(sub_w_) * h_ * c_);
    degraded.resize(size_t(w_) * h_ * c_);
    gatherRows(apply_y_, sub.data(), between_.data(), size_t(sub_w_) * c_);
    gatherColumns(apply_x_, c_, between_.data(), sub_w_, degraded.data(), h_);
}

void Degradation::transpose(const std::vector<float>& residual, std::vector<float>& sub) {
    between_.resize(size_t(sub_w_) * h_ * c_);
    sub.resize(size_t(sub_w_) * sub_h_ * c_);
    gatherColumns(transpose_x_, c_, residual.data(), w_, between_.data(), h_);
    gatherRows(transpose_y_, between_.data(), sub.data(), size_t(sub_w_) * c_);
}

}  // namespace ddt
