#include "convolution_fallback.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>

#include "channel_count.h"

namespace ddt {

constexpr int kLanczosTaps = 6;  // Lanczos3 under magnification: 3 input pixels each side

// One output column's (or row's) taps along one axis of the crop.
struct LanczosTaps {
    std::array<uint32_t, kLanczosTaps> index;
    std::array<float, kLanczosTaps> weight;
    uint32_t cell;    // the crop pixel at or before the sample, for the weights' bilinear lookup
    float fraction;   // and the sample's offset from it, in [0, 1]
};

// The column taps of the last x range blended.
struct ConvolutionFallback::ColumnCache {
    std::mutex mutex;
    std::array<uint32_t, 5> key{};
    std::shared_ptr<const std::vector<LanczosTaps>> taps;
};

namespace {

constexpr int kGaussianRadius = 3;
// Output rows blended per pass: their crop rows' horizontal sums are computed once.
constexpr uint32_t kRowsPerChunk = 64;

uint32_t clampIndex(int64_t i, uint32_t size) { return uint32_t(std::clamp<int64_t>(i, 0, int64_t(size) - 1)); }

double lanczos3(double d) {
    if (d == 0.0) return 1.0;
    if (std::abs(d) >= 3.0) return 0.0;
    const double pi_d = M_PI * d;
    return 3.0 * std::sin(pi_d) * std::sin(pi_d / 3.0) / (pi_d * pi_d);
}

// Output pixel `o` of an axis of `out_size` outputs over `input_size` whole-input pixels
// samples at ((o + 0.5) · input/out − 0.5) (core/image/render.h). The taps are found in
// whole-input coordinates and only then moved into the crop, so a tile's pixels get the same
// weights, bit for bit, as the whole image's.
LanczosTaps tapsAt(uint32_t o, uint32_t out_size, uint32_t input_size, uint32_t crop_start, uint32_t crop_size) {
    const double position = (o + 0.5) * double(input_size) / out_size - 0.5;
    const int64_t base = int64_t(std::floor(position));
    auto inCrop = [&](int64_t i) { return clampIndex(int64_t(clampIndex(i, input_size)) - crop_start, crop_size); };
    LanczosTaps taps;
    double total = 0.0;
    std::array<double, kLanczosTaps> weights;
    for (int k = 0; k < kLanczosTaps; ++k) {
        const int64_t i = base - 2 + k;
        weights[k] = lanczos3(position - double(i));
        total += weights[k];
        taps.index[k] = inCrop(i);
    }
    for (int k = 0; k < kLanczosTaps; ++k) taps.weight[k] = float(weights[k] / total);
    // The weights' bilinear lookup between whole-input pixels cell and cell + 1.
    const double clamped = std::clamp(position, 0.0, double(input_size - 1));
    const int64_t cell = std::min<int64_t>(int64_t(std::floor(clamped)), std::max<int64_t>(int64_t(input_size) - 2, 0));
    taps.cell = inCrop(cell);
    taps.fraction = input_size > 1 ? float(clamped - double(cell)) : 0.0f;
    return taps;
}

// sum[i] = Σ_j weight[j] · row_j[i] for i < count, over the six taps' rows in their order (the
// sum each sample had when it was made alone). One pass the compiler vectorizes.
void sumTaps(const std::array<const float*, kLanczosTaps>& rows, const std::array<float, kLanczosTaps>& weight,
             float* __restrict sum, size_t count) {
    const float* __restrict r0 = rows[0];
    const float* __restrict r1 = rows[1];
    const float* __restrict r2 = rows[2];
    const float* __restrict r3 = rows[3];
    const float* __restrict r4 = rows[4];
    const float* __restrict r5 = rows[5];
    const float w0 = weight[0], w1 = weight[1], w2 = weight[2], w3 = weight[3], w4 = weight[4], w5 = weight[5];
    for (size_t i = 0; i < count; ++i) {
        float value = 0.0f;
        value += w0 * r0[i];
        value += w1 * r1[i];
        value += w2 * r2[i];
        value += w3 * r3[i];
        value += w4 * r4[i];
        value += w5 * r5[i];
        sum[i] = value;
    }
}

std::vector<LanczosTaps> axisTaps(uint32_t begin, uint32_t end, uint32_t out_size, uint32_t input_size,
                                  uint32_t crop_start, uint32_t crop_size) {
    std::vector<LanczosTaps> taps;
    taps.reserve(end - begin);
    for (uint32_t o = begin; o < end; ++o) taps.push_back(tapsAt(o, out_size, input_size, crop_start, crop_size));
    return taps;
}

// The gradient's structure tensor at one pixel: the products of its components.
struct Tensor {
    float xx = 0.0f, yy = 0.0f, xy = 0.0f;
};

// The Gaussian of σ = 1 over radius 3, normalised.
std::array<float, 2 * kGaussianRadius + 1> gaussianTaps() {
    std::array<float, 2 * kGaussianRadius + 1> taps;
    float total = 0.0f;
    for (int k = -kGaussianRadius; k <= kGaussianRadius; ++k) total += taps[k + kGaussianRadius] = std::exp(-0.5f * k * k);
    for (float& v : taps) v /= total;
    return taps;
}

// `field` (width × height) smoothed by the Gaussian along one axis at (x, y), with clamped edges.
Tensor smoothedAt(const std::vector<Tensor>& field, uint32_t width, uint32_t height, uint32_t x, uint32_t y,
                  bool along_x) {
    static const std::array<float, 2 * kGaussianRadius + 1> taps = gaussianTaps();
    Tensor sum;
    for (int k = -kGaussianRadius; k <= kGaussianRadius; ++k) {
        const uint32_t xx = along_x ? clampIndex(int64_t(x) + k, width) : x;
        const uint32_t yy = along_x ? y : clampIndex(int64_t(y) + k, height);
        const Tensor& t = field[size_t(yy) * width + xx];
        const float tap = taps[k + kGaussianRadius];
        sum.xx += tap * t.xx;
        sum.yy += tap * t.yy;
        sum.xy += tap * t.xy;
    }
    return sum;
}

// The surface's weight for a smoothed tensor: T is its trace, |g|² smoothed, and its
// coherence ((λ₁ − λ₂) / (λ₁ + λ₂))² is 1 along a straight edge and near 0 in grain.
float weightOf(const Tensor& t, float grain_share) {
    const float energy = t.xx + t.yy;
    const float contrast = std::clamp((std::log10(energy + 1e-9f) - kLogFlat) / (kLogEdge - kLogFlat), 0.0f, 1.0f);
    if (contrast == 0.0f) return kWeightFlat;  // also where the coherence is 0 / 0
    const float difference = t.xx - t.yy;
    // At most 1 but for rounding: xx · yy ≥ xy² holds for the smoothed sums.
    const float coherence = std::min((difference * difference + 4.0f * t.xy * t.xy) / (energy * energy), 1.0f);
    return kWeightFlat + (kWeightEdge - kWeightFlat) * contrast * (grain_share + (1.0f - grain_share) * coherence);
}

}  // namespace

float grainShareFor(AssumedKernel kernel) { return kernel == AssumedKernel::footprint ? 1.0f : kGrainShare; }

std::vector<float> surfaceWeights(const Image& image, float grain_share) {
    const uint32_t w = image.width, h = image.height, c = image.channels;
    const uint32_t colours = image.hasAlpha() ? c - 1 : c;
    std::vector<float> mean(size_t(w) * h);
    for (size_t p = 0; p < mean.size(); ++p) {
        float sum = 0.0f;
        for (uint32_t k = 0; k < colours; ++k) sum += image.pixels[p * c + k];
        mean[p] = sum / float(colours);
    }
    auto at = [&](int64_t x, int64_t y) { return mean[size_t(clampIndex(y, h)) * w + clampIndex(x, w)]; };
    std::vector<Tensor> tensor(mean.size());
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const int64_t X = x, Y = y;
            const float gx = (at(X + 1, Y - 1) + 2 * at(X + 1, Y) + at(X + 1, Y + 1) - at(X - 1, Y - 1) -
                              2 * at(X - 1, Y) - at(X - 1, Y + 1)) / 8.0f;
            const float gy = (at(X - 1, Y + 1) + 2 * at(X, Y + 1) + at(X + 1, Y + 1) - at(X - 1, Y - 1) -
                              2 * at(X, Y - 1) - at(X + 1, Y - 1)) / 8.0f;
            tensor[size_t(y) * w + x] = {gx * gx, gy * gy, gx * gy};
        }
    mean = {};
    std::vector<Tensor> across(tensor.size());
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) across[size_t(y) * w + x] = smoothedAt(tensor, w, h, x, y, true);
    tensor = {};
    std::vector<float> weights(across.size());
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            weights[size_t(y) * w + x] = weightOf(smoothedAt(across, w, h, x, y, false), grain_share);
    return weights;
}

ConvolutionFallback::ConvolutionFallback(const Image& input, float grain_share)
    : input_(input), weights_(surfaceWeights(input, grain_share)), columns_(std::make_unique<ColumnCache>()) {}

ConvolutionFallback::~ConvolutionFallback() = default;
ConvolutionFallback::ConvolutionFallback(ConvolutionFallback&&) noexcept = default;
ConvolutionFallback& ConvolutionFallback::operator=(ConvolutionFallback&&) noexcept = default;

// The column taps of a window's x range, made once for all its bands: a tile's windows share
// one range, and each tapsAt costs twelve sines (4 % of a photograph's run, measured).
std::shared_ptr<const std::vector<LanczosTaps>> ConvolutionFallback::columnsOf(const RenderWindow& window) const {
    const std::array<uint32_t, 5> key{window.x_begin, window.x_end, window.out.width, window.input_width, window.crop_x};
    std::lock_guard lock(columns_->mutex);
    if (!columns_->taps || columns_->key != key) {
        columns_->taps = std::make_shared<const std::vector<LanczosTaps>>(
            axisTaps(window.x_begin, window.x_end, window.out.width, window.input_width, window.crop_x, input_.width));
        columns_->key = key;
    }
    return columns_->taps;
}

void ConvolutionFallback::blend(const RenderWindow& window, float* rows, size_t row_stride) const {
    withChannelCount(input_.channels, [&](auto channels) {
        blendWith<decltype(channels)::value>(window, rows, row_stride);
    });
}

// blend with the channel count a constant, so that the loops over a pixel's channels unroll.
template <uint32_t c>
void ConvolutionFallback::blendWith(const RenderWindow& window, float* rows, size_t row_stride) const {
    const uint32_t crop_w = input_.width, crop_h = input_.height, width = window.width();
    const size_t row_floats = row_stride ? row_stride : size_t(width) * c;
    const std::shared_ptr<const std::vector<LanczosTaps>> column_taps = columnsOf(window);
    const std::vector<LanczosTaps>& columns = *column_taps;
    const bool integer = input_.sample_type == SampleType::UInt8 || input_.sample_type == SampleType::UInt16;
    const bool alpha = input_.hasAlpha();
    const size_t line = size_t(width) * c;  // floats of one row of horizontal sums
    std::vector<float> across;     // the horizontal pass of crop rows [first_row, first_row + count)
    std::vector<float> convolved(line);
    // The weights' lerps along the columns, per output column, in the cell row of the last
    // output row and the one below: under magnification several output rows share a cell row.
    std::vector<float> top(width), bottom(width);
    uint32_t lerped_cell = UINT32_MAX;
    for (uint32_t chunk = window.y_begin; chunk < window.y_end; chunk += kRowsPerChunk) {
        const uint32_t chunk_end = std::min(window.y_end, chunk + kRowsPerChunk);
        // The taps move down with the output row, so the chunk reads one run of crop rows.
        const uint32_t first_row = tapsAt(chunk, window.out.height, window.input_height, window.crop_y, crop_h).index[0];
        const uint32_t last_row =
            tapsAt(chunk_end - 1, window.out.height, window.input_height, window.crop_y, crop_h).index[kLanczosTaps - 1];
        across.resize(size_t(last_row - first_row + 1) * line);
        for (uint32_t r = first_row; r <= last_row; ++r) {
            const float* source = input_.row(r);
            float* sums = across.data() + size_t(r - first_row) * line;
            for (uint32_t x = 0; x < width; ++x)
                for (uint32_t k = 0; k < c; ++k) {
                    float sum = 0.0f;
                    for (int i = 0; i < kLanczosTaps; ++i) sum += columns[x].weight[i] * source[size_t(columns[x].index[i]) * c + k];
                    sums[size_t(x) * c + k] = sum;
                }
        }
        for (uint32_t y = chunk; y < chunk_end; ++y) {
            const LanczosTaps row = tapsAt(y, window.out.height, window.input_height, window.crop_y, crop_h);
            // Along y, a whole row at a time.
            std::array<const float*, kLanczosTaps> tap_rows;
            for (int j = 0; j < kLanczosTaps; ++j) tap_rows[j] = across.data() + size_t(row.index[j] - first_row) * line;
            sumTaps(tap_rows, row.weight, convolved.data(), line);
            if (row.cell != lerped_cell) {
                const float* w_top = weights_.data() + size_t(row.cell) * crop_w;
                const float* w_bottom = weights_.data() + size_t(std::min(row.cell + 1, crop_h - 1)) * crop_w;
                for (uint32_t x = 0; x < width; ++x) {
                    const LanczosTaps& col = columns[x];
                    const uint32_t right = std::min(col.cell + 1, crop_w - 1);
                    top[x] = w_top[col.cell] + col.fraction * (w_top[right] - w_top[col.cell]);
                    bottom[x] = w_bottom[col.cell] + col.fraction * (w_bottom[right] - w_bottom[col.cell]);
                }
                lerped_cell = row.cell;
            }
            float* out = rows + size_t(y - window.y_begin) * row_floats;
            for (uint32_t x = 0; x < width; ++x) {
                const float surface_weight = top[x] + row.fraction * (bottom[x] - top[x]);
                float* pixel = out + size_t(x) * c;
                const float* blended = convolved.data() + size_t(x) * c;
                for (uint32_t k = 0; k < c; ++k) {
                    float value = surface_weight * pixel[k] + (1.0f - surface_weight) * blended[k];
                    if (integer) value = std::clamp(value, 0.0f, 1.0f);
                    pixel[k] = value;
                }
                if (alpha)
                    for (uint32_t k = 0; k + 1 < c; ++k) pixel[k] = std::min(pixel[k], pixel[c - 1]);
            }
        }
    }
}

}  // namespace ddt
