// The convolution fallback's arrays (glsl/layout.h) and what its kernels share, as core's
// ConvolutionFallback (core/image/convolution_fallback.cpp). Include after common.glsl.
#include "fallback_constants.h"
#include "raster.h"

// rgba32f: the structure tensor (xx, yy, xy) while the weights are made, then the weight in x.
layout(binding = kBindingFallbackWeights, rgba32f) uniform imageBuffer fallback_weights;
layout(binding = kBindingFallbackAcross, rgba32f) uniform imageBuffer fallback_across;

const float kPi = 3.14159265358979;

uint clampIndex(int64_t i, uint size) { return uint(clamp(i, int64_t(0), int64_t(size) - 1)); }

// The Gaussian of σ = 1 over radius 3, normalised as core's: exp in float, summed from −3 up.
float[2 * kFallbackGaussianRadius + 1] gaussianTaps() {
    float taps[2 * kFallbackGaussianRadius + 1];
    float total = 0.0;
    for (int k = -kFallbackGaussianRadius; k <= kFallbackGaussianRadius; ++k) {
        taps[k + kFallbackGaussianRadius] = exp(-0.5 * float(k * k));
        total += taps[k + kFallbackGaussianRadius];
    }
    for (int k = 0; k < 2 * kFallbackGaussianRadius + 1; ++k) taps[k] /= total;
    return taps;
}

// One output column's (or row's) taps along one axis of the crop, as core's tapsAt.
struct LanczosTaps {
    uint index[kFallbackTaps];  // crop pixels
    float weight[kFallbackTaps];
    uint cell;       // the crop pixel at or before the sample, for the weights' bilinear lookup
    float fraction;  // and the sample's offset from it, in [0, 1]
};

// Lanczos3 at offset d from a tap, given sin(π d).
float lanczos3(float d, float sin_pi_d) {
    if (d == 0.0) return 1.0;
    if (abs(d) >= 3.0) return 0.0;
    const float pi_d = kPi * d;
    return 3.0 * sin_pi_d * sin(pi_d / 3.0) / (pi_d * pi_d);
}

// Output pixel `o` of an axis of `out_size` outputs over `input_size` whole-input pixels
// samples at num / den = ((2o + 1) · input − out) / (2 · out) (glsl/raster.h's units): the
// taps are found exactly, in whole-input coordinates, and only then moved into the crop, so
// that a tile's pixels get the whole image's weights.
LanczosTaps tapsAt(uint o, uint out_size, uint input_size, uint crop_start, uint crop_size) {
    const int64_t den = 2 * int64_t(out_size);
    const int64_t num = (2 * int64_t(o) + 1) * int64_t(input_size) - int64_t(out_size);
    const int64_t base = num >= 0 ? num / den : -((den - 1 - num) / den);  // floor(num / den)
    const float offset = float(num - base * den) / float(den);             // in [0, 1)
    // Tap k lies at base − 2 + k, d = offset + 2 − k away: sin(π d) = (−1)^k sin(π · offset).
    const float sin_offset = sin(kPi * offset);
    LanczosTaps taps;
    float weights[kFallbackTaps];
    float total = 0.0;
    for (int k = 0; k < kFallbackTaps; ++k) {
        weights[k] = lanczos3(offset + float(2 - k), (k & 1) == 0 ? sin_offset : -sin_offset);
        total += weights[k];
        taps.index[k] = clampIndex(int64_t(clampIndex(base - 2 + k, input_size)) - int64_t(crop_start), crop_size);
    }
    for (int k = 0; k < kFallbackTaps; ++k) taps.weight[k] = weights[k] / total;
    // The weights' bilinear lookup between whole-input pixels cell and cell + 1.
    const int64_t clamped = sampleCoord(o, input_size, out_size);
    const int64_t cell = min(clamped / den, int64_t(max(int(input_size) - 2, 0)));
    taps.cell = clampIndex(cell - int64_t(crop_start), crop_size);
    taps.fraction = input_size > 1 ? float(clamped - cell * den) / float(den) : 0.0;
    return taps;
}
