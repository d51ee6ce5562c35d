#include "strip_rows.h"

#include <algorithm>
#include <memory>

#include "sample_quantise.h"

namespace ddt {

namespace {

template <typename Sample>
std::vector<Sample>& codesOf(OutputRows& band) {
    if constexpr (sizeof(Sample) == 1) return band.codes8;
    else return band.codes16;
}

}  // namespace

StripRows::StripRows(uint32_t y_begin, uint32_t y_end, size_t row_floats, uint32_t band_rows, uint32_t code_bits)
    : row_floats_(row_floats), code_bits_(code_bits) {
    for (uint32_t y = y_begin; y < y_end; y += band_rows) {
        const uint32_t end = std::min(y_end, y + band_rows);
        const size_t samples = size_t(end - y) * row_floats;
        if (code_bits == 0) {
            bands_.emplace_back(y, end, row_floats);
            continue;
        }
        OutputRows band;
        band.y_begin = y;
        band.y_end = end;
        if (code_bits == 8) band.codes8.resize(samples);
        else band.codes16.resize(samples);
        bands_.push_back(std::move(band));
    }
}

double StripRows::bytes(uint32_t rows, size_t row_floats, uint32_t code_bits) {
    return double(rows) * double(row_floats) * (code_bits ? code_bits / 8 : sizeof(float));
}

void StripRows::render(const HostSurface& surface, RenderWindow window, uint32_t channels) {
    for (OutputRows& band : bands_) {
        window.y_begin = band.y_begin;
        window.y_end = band.y_end;
        if (code_bits_ == 8) renderCodes<uint8_t>(surface, window, channels, band);
        else if (code_bits_ == 16) renderCodes<uint16_t>(surface, window, channels, band);
        else
            surface.renderWindow(window, band.row(band.y_begin, row_floats_) + size_t(window.x_begin) * channels,
                                 row_floats_);
    }
}

// Rendered as floats a few rows at a time, each row's part made codes as the writer would
// make them from the whole row.
template <typename Sample>
void StripRows::renderCodes(const HostSurface& surface, RenderWindow window, uint32_t channels, OutputRows& band) {
    const size_t width = size_t(window.x_end - window.x_begin) * channels, first = size_t(window.x_begin) * channels;
    const uint32_t run = kRowsPerRenderBand;
    const auto scratch = std::make_unique_for_overwrite<float[]>(run * width);
    std::vector<Sample>& codes = codesOf<Sample>(band);
    for (uint32_t y = band.y_begin; y < band.y_end; y += run) {
        RenderWindow rows = window;
        rows.y_begin = y;
        rows.y_end = std::min(band.y_end, y + run);
        surface.renderWindow(rows, scratch.get(), width);
        for (uint32_t r = rows.y_begin; r < rows.y_end; ++r)
            quantiseRowPart(scratch.get() + (r - rows.y_begin) * width,
                            codes.data() + (r - band.y_begin) * row_floats_ + first, first, first + width, row_floats_);
    }
}

}  // namespace ddt
