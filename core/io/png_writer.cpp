#include "png_writer.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "parallel.h"
#include "sample_quantise.h"

namespace ddt {

namespace {

// Rows converted at a time: a few MiB of samples, whatever the size of the caller's band.
constexpr size_t kSliceBytes = size_t(4) << 20;

// 16-bit samples as PNG stores them: big-endian.
void storeBigEndian(const uint16_t* samples, uint8_t* to, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        to[2 * i] = uint8_t(samples[i] >> 8);
        to[2 * i + 1] = uint8_t(samples[i]);
    }
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
                    storeBigEndian(samples.data(), to, row_floats_);
                }
            }
        });
        encoder_->addRows(samples_.data(), rows_here);
    }
}

void PngWriter::writeCodes(const uint8_t* codes, uint32_t count) {
    if (sample_bytes_ != 1) throw std::logic_error("PngWriter: 8-bit codes for a 16-bit file");
    encoder_->addRows(codes, count);
}

void PngWriter::writeCodes(const uint16_t* codes, uint32_t count) {
    if (sample_bytes_ != 2) throw std::logic_error("PngWriter: 16-bit codes for an 8-bit file");
    const size_t row_bytes = row_floats_ * 2;
    const uint32_t slice_rows = uint32_t(std::clamp<size_t>(kSliceBytes / row_bytes, 1, count));
    samples_.resize(size_t(slice_rows) * row_bytes);
    for (uint32_t first = 0; first < count; first += slice_rows) {
        const uint32_t rows_here = std::min(slice_rows, count - first);
        const uint16_t* from = codes + size_t(first) * row_floats_;
        parallelFor(rows_here, 16, [&](size_t begin, size_t end) {
            storeBigEndian(from + begin * row_floats_, samples_.data() + begin * row_bytes, (end - begin) * row_floats_);
        });
        encoder_->addRows(samples_.data(), rows_here);
    }
}

void PngWriter::finish() { encoder_->finish(); }

}  // namespace ddt
