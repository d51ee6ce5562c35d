#include "strip_rows.h"

#include <algorithm>

#include "sample_quantise.h"
#include "uninitialised_vector.h"

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
        RenderWindow part = window;
        part.y_begin = std::max(window.y_begin, band.y_begin);
        part.y_end = std::min(window.y_end, band.y_end);
        if (part.y_begin >= part.y_end) continue;
        if (code_bits_ == 8) renderCodes<uint8_t>(surface, part, channels, band);
        else if (code_bits_ == 16) renderCodes<uint16_t>(surface, part, channels, band);
        else
            surface.renderWindow(part, band.row(part.y_begin, row_floats_) + size_t(part.x_begin) * channels, row_floats_);
    }
}

// Rendered as floats a few rows at a time, each row's part made codes as the writer would
// make them from the whole row. The scratch lives only as long as the call: kept per thread,
// it would sit beside the next strip's reconstruction, the run's peak.
template <typename Sample>
void StripRows::renderCodes(const HostSurface& surface, RenderWindow window, uint32_t channels, OutputRows& band) {
    const size_t width = size_t(window.x_end - window.x_begin) * channels, first = size_t(window.x_begin) * channels;
    const uint32_t run = std::min(kRowsPerRenderBand, window.y_end - window.y_begin);
    UninitialisedVector<float> scratch(run * width);
    std::vector<Sample>& codes = codesOf<Sample>(band);
    for (uint32_t y = window.y_begin; y < window.y_end; y += run) {
        RenderWindow rows = window;
        rows.y_begin = y;
        rows.y_end = std::min(window.y_end, y + run);
        surface.renderWindow(rows, scratch.data(), width);
        for (uint32_t r = rows.y_begin; r < rows.y_end; ++r)
            quantiseRowPart(scratch.data() + (r - rows.y_begin) * width,
                            codes.data() + (r - band.y_begin) * row_floats_ + first, first, first + width, row_floats_);
    }
}

}  // namespace ddt
