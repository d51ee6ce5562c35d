// Rendered output rows on their way to the encoder. They are owned and moved, never copied:
// at ×4 a photo's output is hundreds of megabytes of floats, and each copy of it cost more
// time than encoding a tenth of it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace ddt {

struct OutputRows {
    uint32_t y_begin = 0, y_end = 0;
    std::unique_ptr<float[]> floats;  // (y_end − y_begin) rows; not zeroed when made, as every float is rendered
    // Instead of floats, where the writer takes them (TileOptions::code_bits): the 8- or
    // 16-bit codes it would make of them (app/strip_rows.h), row_floats a row; one of the two.
    std::vector<uint8_t> codes8;
    std::vector<uint16_t> codes16;

    OutputRows() = default;
    OutputRows(uint32_t begin, uint32_t end, size_t row_floats)
        : y_begin(begin), y_end(end), floats(std::make_unique_for_overwrite<float[]>(size_t(end - begin) * row_floats)) {}

    uint32_t rows() const { return y_end - y_begin; }
    float* row(uint32_t y, size_t row_floats) const { return floats.get() + size_t(y - y_begin) * row_floats; }
    // The bytes the rows hold, row_floats samples a row.
    size_t bytes(size_t row_floats) const {
        const size_t samples = size_t(rows()) * row_floats;
        return samples * (!codes8.empty() ? 1 : !codes16.empty() ? 2 : sizeof(float));
    }
    // Drops the rows before y (a retry that gives rows already sent).
    void dropBefore(uint32_t y, size_t row_floats) {
        const size_t dropped = size_t(y - y_begin) * row_floats;
        if (!codes8.empty()) codes8.erase(codes8.begin(), codes8.begin() + dropped);
        else if (!codes16.empty()) codes16.erase(codes16.begin(), codes16.begin() + dropped);
        else std::copy(row(y, row_floats), row(y_end, row_floats), floats.get());
        y_begin = y;
    }
};

}  // namespace ddt
