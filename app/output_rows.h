// Rendered output rows on their way to the encoder. They are owned and moved, never copied:
// at ×4 a photo's output is hundreds of megabytes of floats, and each copy of it cost more
// time than encoding a tenth of it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

namespace ddt {

struct OutputRows {
    uint32_t y_begin = 0, y_end = 0;
    std::unique_ptr<float[]> floats;  // (y_end − y_begin) rows; not zeroed when made, as every float is rendered

    OutputRows() = default;
    OutputRows(uint32_t begin, uint32_t end, size_t row_floats)
        : y_begin(begin), y_end(end), floats(std::make_unique_for_overwrite<float[]>(size_t(end - begin) * row_floats)) {}

    uint32_t rows() const { return y_end - y_begin; }
    float* row(uint32_t y, size_t row_floats) const { return floats.get() + size_t(y - y_begin) * row_floats; }
};

}  // namespace ddt
