// A strip's output rows while its tiles render into them at once (app/tiled_upscale.cpp), cut
// into the bands they go out in. Where the writer makes its floats 8- or 16-bit codes and
// nothing else (ImageWriter::codeBits), the rows are kept as those codes, a quarter or half
// of the floats' bytes, and each band goes out as floats that make the same codes again: the
// file is the one floats would give, byte for byte.
#pragma once

#include <cstddef>
#include <cstdint>
#include <variant>
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

    // Renders `surface`'s columns [window.x_begin, window.x_end) (window's rows are ignored)
    // into every band. Tiles of other columns may render at the same time.
    void render(const HostSurface& surface, RenderWindow window, uint32_t channels);

    uint32_t bandCount() const { return uint32_t(bands_.size()); }
    // Band k as floats, taken out (a caller may render more tiles into it before it goes).
    OutputRows takeBand(uint32_t k);

private:
    struct Band {
        uint32_t y_begin, y_end;
        OutputRows floats;                                                // code_bits 0
        std::variant<std::vector<uint8_t>, std::vector<uint16_t>> codes;  // else
    };
    template <typename Sample>
    void renderCodes(const HostSurface& surface, RenderWindow window, uint32_t channels, Band& band);
    template <typename Sample>
    OutputRows floatsOf(const Band& band) const;

    size_t row_floats_;
    uint32_t code_bits_;
    std::vector<Band> bands_;
};

}  // namespace ddt
