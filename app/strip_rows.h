// A strip's output rows while its tiles render into them at once (app/tiled_upscale.cpp), cut
// into the bands they go out in. Where the writer makes its floats 8- or 16-bit codes and
// nothing else (ImageWriter::codeBits), the rows are kept and go out as those codes, a quarter
// or half of the floats' bytes, each made as the writer would make it from the whole row: the
// file is the one floats would give, byte for byte.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "backend.h"
#include "output_rows.h"
#include "render.h"

namespace ddt {

class StripRows {
public:
    // Output rows [y_begin, y_end) of row_floats floats, in bands of band_rows; code_bits 8,
    // 16 or 0 (floats).
    StripRows(uint32_t y_begin, uint32_t y_end, size_t row_floats, uint32_t band_rows, uint32_t code_bits);

    // The bytes such a strip holds.
    static double bytes(uint32_t rows, size_t row_floats, uint32_t code_bits);

    // Renders `surface`'s window, its rows where they meet the strip's, into the bands. Other
    // windows (other columns, or other rows) may render at the same time.
    void render(const HostSurface& surface, RenderWindow window, uint32_t channels);

    uint32_t bandCount() const { return uint32_t(bands_.size()); }
    // Band k, taken out: floats, or codes.
    OutputRows takeBand(uint32_t k) { return std::move(bands_[k]); }

private:
    template <typename Sample>
    void renderCodes(const HostSurface& surface, RenderWindow window, uint32_t channels, OutputRows& band);

    size_t row_floats_;
    uint32_t code_bits_;
    std::vector<OutputRows> bands_;
};

}  // namespace ddt
