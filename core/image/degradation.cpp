#include "degradation.h"

#include <algorithm>
#include <cstring>

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

// Along y: row o of the output gathers whole rows (row_floats floats each; input row i at
// source(i)), a block of the row at a time so that the sum stays in the L1 cache while its
// terms stream in.
template <typename Source>
void gatherRow(const AxisTaps& taps, uint32_t o, Source source, float* out, size_t row_floats) {
    const size_t kBlock = 1024;  // floats
    const uint32_t first = taps.first[o], last = taps.first[o + 1];
    for (size_t block = 0; block < row_floats; block += kBlock) {
        float* row = out + block;
        const size_t n = std::min(kBlock, row_floats - block);
        if (first == last) {
            std::fill_n(row, n, 0.0f);
            continue;
        }
        // 0 + the first term, as a sum from 0 has it (−0 becomes +0).
        const float* in = source(taps.index[first]) + block;
        const float g = taps.weight[first];
        for (size_t i = 0; i < n; ++i) row[i] = 0.0f + g * in[i];
        for (uint32_t j = first + 1; j < last; ++j) {
            const float* in = source(taps.index[j]) + block;
            const float g = taps.weight[j];
            for (size_t i = 0; i < n; ++i) row[i] += g * in[i];
        }
    }
}

// Along x, within one row: output pixel o gathers pixels of the input row. A run's outputs are
// summed for every float of the input's span at once (the filter at every input, of which the
// run keeps those at its outputs' first taps), in `scratch`; each keeps its terms' order.
template <uint32_t C>
void gatherColumns(const ColumnGather& gather, const float* in, float* out, std::vector<float>& scratch) {
    for (const TapRun& run : gather.runs) {
        const size_t span = (size_t(run.count - 1) * run.in_step + 1) * C;
        scratch.resize(span);
        float* sums = scratch.data();
        const float* base = in + size_t(run.in_first) * C;
        const float* weights = run.weights.data();
        const size_t taps = run.weights.size();
        // Blocks of kBlock sums stay in registers over all the taps.
        constexpr size_t kBlock = 64;
        size_t m0 = 0;
        for (; m0 + kBlock <= span; m0 += kBlock) {
            float block[kBlock];
            for (size_t i = 0; i < kBlock; ++i) block[i] = 0.0f + weights[0] * base[m0 + i];
            for (size_t t = 1; t < taps; ++t)
                for (size_t i = 0; i < kBlock; ++i) block[i] += weights[t] * base[m0 + t * C + i];
            std::copy_n(block, kBlock, sums + m0);
        }
        for (size_t m = m0; m < span; ++m) {
            float sum = 0.0f + weights[0] * base[m];
            for (size_t t = 1; t < taps; ++t) sum += weights[t] * base[m + t * C];
            sums[m] = sum;
        }
        // The run's fields as locals: the stores below could alias them.
        const size_t count = run.count, out_stride = size_t(run.out_step) * C, in_stride = size_t(run.in_step) * C;
        float* to = out + size_t(run.out_first) * C;
        for (size_t j = 0; j < count; ++j) std::memcpy(to + j * out_stride, sums + j * in_stride, C * sizeof(float));
    }
    const AxisTaps& taps = gather.taps;
    for (uint32_t o : gather.loose) {
        PixelVector<C> sum = {};
        for (uint32_t j = taps.first[o]; j < taps.first[o + 1]; ++j)
            sum += taps.weight[j] * loadPixel<C>(in + size_t(taps.index[j]) * C);
        storePixel<C>(out + size_t(o) * C, sum);
    }
}

// The most rows of its input one output of `taps` spans.
uint32_t widestSpan(const AxisTaps& taps) {
    uint32_t widest = 1;
    for (uint32_t o = 0; o < taps.outputs(); ++o) {
        if (taps.first[o] == taps.first[o + 1]) continue;
        const auto [lo, hi] = std::minmax_element(taps.index.begin() + taps.first[o], taps.index.begin() + taps.first[o + 1]);
        widest = std::max(widest, *hi - *lo + 1);
    }
    return widest;
}

// The runs of `taps` (of at least a few outputs each) and the outputs left over.
ColumnGather columnGatherOf(AxisTaps taps) {
    // Fewer outputs than this stay loose: a run's filter costs its span's floats.
    const uint32_t kShortestRun = 4;
    ColumnGather gather{std::move(taps), {}, {}};
    const AxisTaps& t = gather.taps;
    std::vector<TapRun> runs;
    std::vector<std::vector<uint32_t>> members;  // per run, its outputs
    std::vector<uint32_t> loose;
    for (uint32_t o = 0; o < t.outputs(); ++o) {
        const uint32_t first = t.first[o], last = t.first[o + 1];
        bool consecutive = first < last;
        for (uint32_t j = first; consecutive && j < last; ++j) consecutive = t.index[j] == t.index[first] + (j - first);
        if (!consecutive) {
            loose.push_back(o);
            continue;
        }
        const std::vector<float> weights(t.weight.begin() + first, t.weight.begin() + last);
        const uint32_t start = t.index[first];
        // The latest run with these weights, if o continues it.
        size_t found = runs.size();
        for (size_t r = runs.size(); r-- > 0;)
            if (runs[r].weights == weights) {
                found = r;
                break;
            }
        bool extends = false;
        if (found < runs.size()) {
            TapRun& run = runs[found];
            const uint32_t last_out = members[found].back(), last_in = run.in_first + (run.count - 1) * run.in_step;
            if (run.count == 1 && o > last_out && start > last_in) {
                run.out_step = o - last_out;
                run.in_step = start - last_in;
                extends = true;
            } else if (run.count > 1) {
                extends = o == last_out + run.out_step && start == last_in + run.in_step;
            }
        }
        if (extends) {
            ++runs[found].count;
            members[found].push_back(o);
        } else {
            runs.push_back({o, 1, start, 1, 1, weights});
            members.push_back({o});
        }
    }
    for (size_t r = 0; r < runs.size(); ++r) {
        if (runs[r].count >= kShortestRun) gather.runs.push_back(std::move(runs[r]));
        else loose.insert(loose.end(), members[r].begin(), members[r].end());
    }
    std::sort(loose.begin(), loose.end());
    gather.loose = std::move(loose);
    return gather;
}

}  // namespace

Degradation::Degradation(uint32_t width, uint32_t height, uint32_t channels, const DegradationModel& model)
    : w_(width), h_(height), c_(channels), sub_w_(width * kSupersampling), sub_h_(height * kSupersampling),
      apply_x_(columnGatherOf(applyTaps(width, degradationTaps(model.kernel, model.width_x)))),
      transpose_x_(columnGatherOf(transposeTaps(apply_x_.taps, sub_w_))),
      apply_y_(applyTaps(height, degradationTaps(model.kernel, model.width_y))),
      transpose_y_(transposeTaps(apply_y_, sub_h_)),
      transpose_rows_(widestSpan(transpose_y_)) {}

// Each output row is done by one task from its own copy of the row between the two passes.
void Degradation::apply(const float* sub, float* degraded) const {
    const size_t sub_row = size_t(sub_w_) * c_;
    withChannelCount(c_, [&](auto channels) {
        constexpr uint32_t c = decltype(channels)::value;
        parallelFor(h_, kGrain, [&](size_t begin, size_t end) {
            std::vector<float> between(sub_row), scratch;
            for (size_t y = begin; y < end; ++y) {
                gatherRow(apply_y_, uint32_t(y), [&](uint32_t row) { return sub + row * sub_row; }, between.data(), sub_row);
                gatherColumns<c>(apply_x_, between.data(), degraded + y * w_ * c, scratch);
            }
        });
    });
}

// Each task keeps the rows between the two passes that its output rows need in a ring: the
// rows an output gathers increase with it, so a row is computed once per task.
void Degradation::transpose(const float* residual, float* sub) const {
    const size_t sub_row = size_t(sub_w_) * c_;
    withChannelCount(c_, [&](auto channels) {
        constexpr uint32_t c = decltype(channels)::value;
        parallelFor(sub_h_, kGrain, [&](size_t begin, size_t end) {
            std::vector<float> ring(transpose_rows_ * sub_row);
            std::vector<uint32_t> ring_row(transpose_rows_, UINT32_MAX);  // the input row each slot holds
            std::vector<float> scratch;
            auto between = [&](uint32_t y) {
                const uint32_t slot = y % transpose_rows_;
                float* row = ring.data() + slot * sub_row;
                if (ring_row[slot] != y) {
                    gatherColumns<c>(transpose_x_, residual + size_t(y) * w_ * c, row, scratch);
                    ring_row[slot] = y;
                }
                return row;
            };
            for (size_t o = begin; o < end; ++o) {
                // Every row this output needs, first, so that none evicts another while in use.
                for (uint32_t j = transpose_y_.first[o]; j < transpose_y_.first[o + 1]; ++j) between(transpose_y_.index[j]);
                gatherRow(transpose_y_, uint32_t(o), between, sub + o * sub_row, sub_row);
            }
        });
    });
}

}  // namespace ddt
