#include "png_writer.h"

#include <algorithm>
#include <bit>
#include <stdexcept>

#include "parallel.h"
#include "png_metadata.h"

namespace ddt {

namespace {

// Rows converted at a time: a few MiB of samples, whatever the size of the caller's band.
constexpr size_t kSliceBytes = size_t(4) << 20;

}  // namespace

PngWriter::PngWriter(const OIIO::ImageSpec& spec, PngEncoder::Sink sink) {
    if (spec.format != OIIO::TypeDesc::UINT8 && spec.format != OIIO::TypeDesc::UINT16)
        throw std::invalid_argument("PNG samples are 8 or 16 bits");
    type_ = spec.format;
    row_floats_ = size_t(spec.width) * size_t(spec.nchannels);
    PngMetadata metadata = pngMetadata(spec);
    left_out_ = std::move(metadata.left_out);
    const PngFormat format{uint32_t(spec.width), uint32_t(spec.height), uint32_t(spec.nchannels), uint32_t(type_.size() * 8)};
    encoder_ = std::make_unique<PngEncoder>(format, metadata.chunks, std::move(sink));
}

PngWriter::~PngWriter() = default;

void PngWriter::writeRows(const float* rows, uint32_t count) {
    const size_t sample_bytes = type_.size();
    const size_t row_bytes = row_floats_ * sample_bytes;
    const uint32_t slice_rows = uint32_t(std::clamp<size_t>(kSliceBytes / row_bytes, 1, count));
    samples_.resize(size_t(slice_rows) * row_bytes);
    for (uint32_t first = 0; first < count; first += slice_rows) {
        const uint32_t rows_here = std::min(slice_rows, count - first);
        parallelFor(rows_here, 16, [&](size_t begin, size_t end) {
            for (size_t y = begin; y < end; ++y) {
                uint8_t* to = samples_.data() + y * row_bytes;
                // OpenImageIO's own conversion, a row a call as its PNG writer made it: it rounds
                // 4 values at a time with roundf and the rest by adding 0.5, which differ for
                // one float (the one whose product is the float just below 0.5). Its writer may
                // also split a row among its threads (narrow rows, measured), so that value
                // alone can round otherwise than it did.
                OIIO::convert_pixel_values(OIIO::TypeDesc::FLOAT, rows + (first + y) * row_floats_, type_, to, int(row_floats_));
                if (sample_bytes == 2 && std::endian::native == std::endian::little)  // PNG is big-endian
                    for (size_t i = 0; i < row_floats_; ++i) std::swap(to[2 * i], to[2 * i + 1]);
            }
        });
        encoder_->addRows(samples_.data(), rows_here);
    }
}

void PngWriter::finish() { encoder_->finish(); }

}  // namespace ddt
