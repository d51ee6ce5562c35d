#include "strip_rows.h"

#include <algorithm>
#include <memory>

#include "sample_quantise.h"

namespace ddt {

StripRows::StripRows(uint32_t y_begin, uint32_t y_end, size_t row_floats, uint32_t band_rows, uint32_t code_bits)
    : row_floats_(row_floats), code_bits_(code_bits) {
    for (uint32_t y = y_begin; y < y_end; y += band_rows) {
        Band band{y, std::min(y_end, y + band_rows), {}, {}};
        const size_t samples = size_t(band.y_end - band.y_begin) * row_floats;
        if (code_bits == 8) band.codes = std::vector<uint8_t>(samples);
        else if (code_bits == 16) band.codes = std::vector<uint16_t>(samples);
        else band.floats = OutputRows(band.y_begin, band.y_end, row_floats);
        bands_.push_back(std::move(band));
    }
}

double StripRows::bytes(uint32_t rows, size_t row_floats, uint32_t code_bits) {
    return double(rows) * double(row_floats) * (code_bits ? code_bits / 8 : sizeof(float));
}

void StripRows::render(const HostSurface& surface, RenderWindow window, uint32_t channels) {
    for (Band& band : bands_) {
        window.y_begin = band.y_begin;
        window.y_end = band.y_end;
        if (code_bits_ == 8) renderCodes<uint8_t>(surface, window, channels, band);
        else if (code_bits_ == 16) renderCodes<uint16_t>(surface, window, channels, band);
        else
            surface.renderWindow(window, band.floats.row(band.y_begin, row_floats_) + size_t(window.x_begin) * channels,
                                 row_floats_);
    }
}

// Rendered as floats a few rows at a time, each row's part made codes as the writer would
// make them from the whole row.
template <typename Sample>
void StripRows::renderCodes(const HostSurface& surface, RenderWindow window, uint32_t channels, Band& band) {
    const size_t width = size_t(window.x_end - window.x_begin) * channels, first = size_t(window.x_begin) * channels;
    const uint32_t run = kRowsPerRenderBand;
    const auto scratch = std::make_unique_for_overwrite<float[]>(run * width);
    std::vector<Sample>& codes = std::get<std::vector<Sample>>(band.codes);
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

template <typename Sample>
OutputRows StripRows::floatsOf(const Band& band) const {
    OutputRows rows(band.y_begin, band.y_end, row_floats_);
    const std::vector<Sample>& codes = std::get<std::vector<Sample>>(band.codes);
    std::transform(codes.begin(), codes.end(), rows.floats.get(), [](Sample code) { return codeValue(code); });
    return rows;
}

OutputRows StripRows::takeBand(uint32_t k) {
    Band& band = bands_[k];
    OutputRows rows = code_bits_ == 8    ? floatsOf<uint8_t>(band)
                      : code_bits_ == 16 ? floatsOf<uint16_t>(band)
                                         : std::move(band.floats);
    band.codes = std::vector<uint8_t>();  // given back
    return rows;
}

}  // namespace ddt
