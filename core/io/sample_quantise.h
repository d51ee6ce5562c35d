// Float samples to the 8- or 16-bit codes OpenImageIO 2.4's writers made of them, shared by
// ddtup's own PNG and JPEG writers so that their files stay byte-identical to OpenImageIO's.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

namespace ddt {

// A row of floats as the samples OpenImageIO 2.4's writers made of them (fmath.h's
// convert_type<float, uint8_t> and <float, uint16_t>, through convert_pixel_values, one row a
// call): values in groups of 4 are scaled by Max, rounded half away from zero (roundf, in
// Debian's build) and clamped to [0, Max]; the last n % 4 get 0.5 added to the scaled value,
// are clamped, and truncated. The two differ for one float, the one whose product is the
// float just below 0.5. NaN becomes 0 both ways (OpenImageIO's clamp keeps the bound there).
// Written out so that the compiler vectorises it: a call of roundf per sample was a quarter
// of the PNG encoder's time.
// The first way on its own, one value: rounded half away from zero and clamped.
template <typename Sample>
Sample quantiseRounded(float value) {
    constexpr float kMax = float(std::numeric_limits<Sample>::max());
    float scaled = value * kMax;
    scaled = scaled == scaled ? scaled : 0.0f;
    scaled = std::clamp(scaled, -1.0f, kMax + 1.0f);
    const int32_t whole = int32_t(scaled);
    const float rest = scaled - float(whole);
    const int32_t rounded = whole + (rest >= 0.5f) - (rest <= -0.5f);
    return Sample(std::clamp(rounded, int32_t(0), int32_t(kMax)));
}

// Samples [begin, end) of a row of n floats as quantiseRow of the whole row makes them:
// `values` and `samples` point at sample `begin`. Each value's way depends only on its place
// in the row, so a row may be made piece by piece (a tile's columns at a time).
template <typename Sample>
void quantiseRowPart(const float* values, Sample* samples, size_t begin, size_t end, size_t n) {
    // Eight values at a time in SIMD vectors (the GCC/Clang vector extension; a build without
    // 256-bit vectors splits them in two); a comparison gives −1 where it holds. The first
    // n / 4 · 4 values of the row take quantiseRounded's rule, whatever the vectors' width.
    typedef float Float8 __attribute__((vector_size(32)));
    typedef int32_t Int8 __attribute__((vector_size(32)));
    constexpr float kMax = float(std::numeric_limits<Sample>::max());
    const Float8 low = Float8{} - 1.0f, high = Float8{} + (kMax + 1.0f);
    const Int8 zero = {}, top = Int8{} + int32_t(kMax);
    const size_t rounded_end = std::clamp(n / 4 * 4, begin, end) - begin, count = end - begin;
    size_t i = 0;
    for (; i + 8 <= rounded_end; i += 8) {
        Float8 scaled;
        std::memcpy(&scaled, values + i, sizeof scaled);
        scaled *= kMax;
        // Rounding the value clamped to [−1, Max + 1] and clamping the result to [0, Max]
        // gives what clamping the rounded value does; the clamp keeps the conversion defined.
        scaled = scaled == scaled ? scaled : Float8{};  // NaN → 0
        scaled = scaled < low ? low : scaled;
        scaled = scaled > high ? high : scaled;
        const Int8 whole = __builtin_convertvector(scaled, Int8);             // towards zero
        const Float8 rest = scaled - __builtin_convertvector(whole, Float8);  // exact
        Int8 rounded = whole - (rest >= 0.5f) + (rest <= -0.5f);
        rounded = rounded < zero ? zero : rounded;
        rounded = rounded > top ? top : rounded;
        for (int k = 0; k < 8; ++k) samples[i + k] = Sample(rounded[k]);
    }
    for (; i < rounded_end; ++i) samples[i] = quantiseRounded<Sample>(values[i]);
    for (; i < count; ++i) {
        const float scaled = values[i] * kMax + 0.5f;
        samples[i] = scaled == scaled ? Sample(std::clamp(scaled, 0.0f, kMax)) : Sample(0);
    }
}

template <typename Sample>
void quantiseRow(const float* values, Sample* samples, size_t n) {
    quantiseRowPart(values, samples, 0, n, n);
}

}  // namespace ddt
