// The reconstruction's degradation D and its transpose (core/image/degradation.h) against the
// definition written here as scatters: each input adds its weighted taps into the outputs they
// land on, pixel by pixel and tap by tap. A gather that keeps that order of terms gives every
// sum bit for bit, however it groups the outputs (the filter runs along x, the loose ends).
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <vector>

#include "degradation.h"
#include "reconstruct.h"

namespace {

using namespace ddt;

// The supersample t steps from pixel i's centre, clamped into the axis (the model's border).
uint32_t centreSample(uint32_t i, int t, uint32_t supersamples) {
    return uint32_t(std::clamp(int(i * kSupersampling + kSupersampling / 2) + t, 0, int(supersamples) - 1));
}

// Along one axis: output pixel i of D sums taps[t + r] · supersample centre(i) + t; the sums
// start from 0 and take their terms in t's order (one output row: `run` floats per position).
void scatterApply(const std::vector<float>& taps, uint32_t pixels, const float* in, size_t in_stride, float* out,
                  size_t out_stride, size_t run) {
    const int r = int(taps.size() / 2);
    for (uint32_t i = 0; i < pixels; ++i) {
        float* to = out + i * out_stride;
        std::fill_n(to, run, 0.0f);
        for (int t = -r; t <= r; ++t) {
            const float* from = in + centreSample(i, t, pixels * kSupersampling) * in_stride;
            for (size_t k = 0; k < run; ++k) to[k] += taps[t + r] * from[k];
        }
    }
}

// Dᵀ along one axis: each pixel i scatters taps[t + r] · its value onto supersample
// centre(i) + t, pixel by pixel, tap by tap, into sums that start from 0.
void scatterTranspose(const std::vector<float>& taps, uint32_t pixels, const float* in, size_t in_stride, float* out,
                      size_t out_stride, size_t run) {
    const int r = int(taps.size() / 2);
    for (uint32_t s = 0; s < pixels * kSupersampling; ++s) std::fill_n(out + s * out_stride, run, 0.0f);
    for (uint32_t i = 0; i < pixels; ++i)
        for (int t = -r; t <= r; ++t) {
            float* to = out + centreSample(i, t, pixels * kSupersampling) * out_stride;
            for (size_t k = 0; k < run; ++k) to[k] += taps[t + r] * in[i * in_stride + k];
        }
}

struct Case {
    uint32_t w, h, c;
    AssumedKernel kernel;
    double scale;
};

}  // namespace

TEST_CASE("degradation: D and Dᵀ equal their definition as scatters, bit for bit") {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    std::vector<Case> cases;
    // Widths from 1 (every output a clamped end) to well past a run's shortest length.
    for (uint32_t w : {1u, 2u, 3u, 5u, 8u, 13u, 40u, 97u})
        for (uint32_t c : {1u, 3u, 4u})
            for (AssumedKernel kernel : {AssumedKernel::mixed, AssumedKernel::footprint, AssumedKernel::box,
                                         AssumedKernel::bicubic, AssumedKernel::lanczos3})
                for (double scale : {1.5, 2.0, 4.0}) cases.push_back({w, 7 + w % 5, c, kernel, scale});
    for (const Case& k : cases) {
        CAPTURE(k.w, k.h, k.c, int(k.kernel), k.scale);
        const DegradationModel model = degradationFor(k.scale, k.scale, k.kernel);
        const Degradation degradation(k.w, k.h, k.c, model);
        const std::vector<float> taps_x = degradationTaps(model.kernel, model.width_x),
                                 taps_y = degradationTaps(model.kernel, model.width_y);
        const uint32_t sub_w = k.w * kSupersampling, sub_h = k.h * kSupersampling;

        std::vector<float> sub(size_t(sub_w) * sub_h * k.c), pixels(size_t(k.w) * k.h * k.c);
        for (float& v : sub) v = value(random);
        for (float& v : pixels) v = value(random) - 0.5f;  // residuals take either sign

        // D: along y (whole supersample rows), then along x within each row.
        std::vector<float> between(size_t(sub_w) * k.h * k.c), expected(pixels.size()), got(pixels.size());
        const size_t sub_row = size_t(sub_w) * k.c;
        scatterApply(taps_y, k.h, sub.data(), sub_row, between.data(), sub_row, sub_row);
        for (uint32_t y = 0; y < k.h; ++y)
            scatterApply(taps_x, k.w, between.data() + y * sub_row, k.c, expected.data() + size_t(y) * k.w * k.c, k.c,
                         k.c);
        degradation.apply(sub.data(), got.data());
        CHECK(got == expected);

        // Dᵀ: along x within each pixel row, then along y.
        std::vector<float> across(size_t(sub_w) * k.h * k.c), expected_sub(sub.size()), got_sub(sub.size());
        for (uint32_t y = 0; y < k.h; ++y)
            scatterTranspose(taps_x, k.w, pixels.data() + size_t(y) * k.w * k.c, k.c, across.data() + y * sub_row, k.c,
                             k.c);
        scatterTranspose(taps_y, k.h, across.data(), sub_row, expected_sub.data(), sub_row, sub_row);
        degradation.transpose(pixels.data(), got_sub.data());
        CHECK(got_sub == expected_sub);
    }
}
