#include "png_writer.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "parallel.h"

namespace ddt {

namespace {

// Rows converted at a time: a few MiB of samples, whatever the size of the caller's band.
constexpr size_t kSliceBytes = size_t(4) << 20;

// A row of floats as the samples OpenImageIO 2.4's PNG writer made of them (fmath.h's
// convert_type<float, uint8_t> and <float, uint16_t>, through convert_pixel_values, one row a
// call): values in groups of 4 are scaled by Max, rounded half away from zero (roundf, in
// Debian's build) and clamped to [0, Max]; the last n % 4 get 0.5 added to the scaled value,
// are clamped, and truncated. The two differ for one float, the one whose product is the
// float just below 0.5. Written out so that the compiler vectorises it: a call of roundf per
// sample was a quarter of the encoder's time. Samples are finite (the renderer's values).
template <typename Sample>
void quantiseRow(const float* values, Sample* samples, size_t n) {
    // Four values at a time in SIMD vectors (the GCC/Clang vector extension); a comparison
    // gives −1 where it holds.
    typedef float Float4 __attribute__((vector_size(16)));
    typedef int32_t Int4 __attribute__((vector_size(16)));
    constexpr float kMax = float(std::numeric_limits<Sample>::max());
    const Float4 low = Float4{} - 1.0f, high = Float4{} + (kMax + 1.0f);
    const Int4 zero = {}, top = Int4{} + int32_t(kMax);
    const size_t grouped = n / 4 * 4;
    for (size_t i = 0; i < grouped; i += 4) {
        Float4 scaled;
        std::memcpy(&scaled, values + i, sizeof scaled);
        scaled *= kMax;
        // Rounding the value clamped to [−1, Max + 1] and clamping the result to [0, Max]
        // gives what clamping the rounded value does; the clamp keeps the conversion defined.
        scaled = scaled < low ? low : scaled;
        scaled = scaled > high ? high : scaled;
        const Int4 whole = __builtin_convertvector(scaled, Int4);             // towards zero
        const Float4 rest = scaled - __builtin_convertvector(whole, Float4);  // exact
        Int4 rounded = whole - (rest >= 0.5f) + (rest <= -0.5f);
        rounded = rounded < zero ? zero : rounded;
        rounded = rounded > top ? top : rounded;
        for (int k = 0; k < 4; ++k) samples[i + k] = Sample(rounded[k]);
    }
    for (size_t i = grouped; i < n; ++i) samples[i] = Sample(std::clamp(values[i] * kMax + 0.5f, 0.0f, kMax));
}

}  // namespace

PngWriter::PngWriter(const PngFormat& format, const PngMetadataSource& metadata, PngEncoder::Sink sink) {
    if (format.bit_depth != 8 && format.bit_depth != 16) throw std::invalid_argument("PNG samples are 8 or 16 bits");
    if (metadata.channels != format.channels) throw std::invalid_argument("the metadata is for another colour model");
    sample_bytes_ = format.bit_depth / 8;
    row_floats_ = size_t(format.width) * format.channels;
    PngMetadata chunks = pngMetadata(metadata);
    left_out_ = std::move(chunks.left_out);
    encoder_ = std::make_unique<PngEncoder>(format, chunks.chunks, std::move(sink));
}

PngWriter::~PngWriter() = default;

void PngWriter::writeRows(const float* rows, uint32_t count) {
    const size_t sample_bytes = sample_bytes_;
    const size_t row_bytes = row_floats_ * sample_bytes;
    const uint32_t slice_rows = uint32_t(std::clamp<size_t>(kSliceBytes / row_bytes, 1, count));
    samples_.resize(size_t(slice_rows) * row_bytes);
    for (uint32_t first = 0; first < count; first += slice_rows) {
        const uint32_t rows_here = std::min(slice_rows, count - first);
        parallelFor(rows_here, 16, [&](size_t begin, size_t end) {
            for (size_t y = begin; y < end; ++y) {
                uint8_t* to = samples_.data() + y * row_bytes;
                // OpenImageIO's writer may also split a row among its threads (narrow rows,
                // measured), so the one float quantiseRow's two ways differ for can round
                // otherwise than it did there.
                const float* values = rows + (first + y) * row_floats_;
                if (sample_bytes == 1) {
                    quantiseRow(values, to, row_floats_);
                } else {
                    std::vector<uint16_t> samples(row_floats_);
                    quantiseRow(values, samples.data(), row_floats_);
                    for (size_t i = 0; i < row_floats_; ++i) {  // PNG is big-endian
                        to[2 * i] = uint8_t(samples[i] >> 8);
                        to[2 * i + 1] = uint8_t(samples[i]);
                    }
                }
            }
        });
        encoder_->addRows(samples_.data(), rows_here);
    }
}

void PngWriter::finish() { encoder_->finish(); }

}  // namespace ddt
