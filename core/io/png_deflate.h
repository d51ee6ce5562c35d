// Deflating one piece of a zlib stream whose pieces are compressed in parallel (the pigz
// technique): raw deflate primed with the bytes just before the piece as its dictionary, ended
// by a sync flush, which aligns the output to a byte so that the next piece can follow, or,
// for the last piece, by the final block.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace ddt {

// The two compressors (measured, see core/io/png_encoder.cpp): ISA-L's igzip at level 1
// deflates 7 times as fast as zlib at level 6 and, on filtered photographs, comes out far
// smaller than zlib's level 6 on the unfiltered rows; on flat images (drawings, large areas of
// one colour) its shallow match search loses 20 to 35 % to zlib, which is fast on such data.
enum class Deflater { Isal, Zlib };

// One compressor's reusable state: a piece at a time, on one thread at a time.
class PieceDeflater {
public:
    PieceDeflater();
    ~PieceDeflater();
    PieceDeflater(PieceDeflater&&) noexcept;
    PieceDeflater& operator=(PieceDeflater&&) noexcept;

    // Compresses `size` bytes at `in` into `out` (grown as needed, never shrunk) and returns the
    // compressed size. The dictionary is at most 32 KiB. `isal_level` is ISA-L's level, 0 to 3.
    size_t deflate(Deflater deflater, int isal_level, const uint8_t* dictionary, size_t dictionary_size, const uint8_t* in,
                   size_t size, bool last, std::vector<uint8_t>& out);

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace ddt
