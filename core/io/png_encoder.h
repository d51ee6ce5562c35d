// A PNG encoder that filters and deflates on ddtup's thread pool and streams its output.
//
// The pigz technique: the filtered rows are cut into chunks of about Options::chunk_bytes,
// and each chunk is deflated on its own, primed with the last 32 KiB of the chunk before it
// as the dictionary and ended by a sync flush (the last by a final block), so that the pieces
// join into one zlib stream; its Adler-32 is combined from the chunks'. Each piece becomes
// one IDAT chunk. The output depends only on the options, never on the number of threads.
// Rows arrive in any number of calls; only a batch of chunks (a few per thread) is held, so
// memory does not grow with the image's height.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "png_filter.h"

namespace ddt {

// The image data's layout (the IHDR chunk): not interlaced, no palette.
struct PngFormat {
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t channels = 0;   // 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA
    uint32_t bit_depth = 8;  // 8 or 16 bits a sample

    size_t rowBytes() const { return size_t(width) * channels * (bit_depth / 8); }
};

// A chunk the caller adds before the image data (metadata): its four-letter type and data.
struct PngChunk {
    std::string type;
    std::string data;
};

class PngEncoder {
public:
    struct Options {
        // Filtered bytes deflated as one piece: a smaller piece costs size at its boundaries
        // (0.1 to 0.6 % at 128 KiB), a larger one holds more memory per thread.
        size_t chunk_bytes = size_t(1) << 18;
        PngFilter filter = PngFilter::PieceAdaptive;
        int isal_level = 1;           // ISA-L's level, 0 to 3, for pieces that are not flat
        bool zlib_for_flat = true;    // flat pieces through zlib (see png_encoder.cpp)
        bool try_unfiltered = true;   // flat and noise-like pieces also deflated unfiltered, the smaller kept
    };

    // Receives the file's bytes in order. It may throw to stop the encoder (a full disk).
    using Sink = std::function<void(const uint8_t* data, size_t size)>;

    // Writes the signature, IHDR and `metadata` (chunks that belong before the image data).
    // Throws std::invalid_argument for a format PNG cannot hold.
    PngEncoder(const PngFormat& format, const std::vector<PngChunk>& metadata, Sink sink);
    PngEncoder(const PngFormat& format, const std::vector<PngChunk>& metadata, Sink sink, const Options& options);
    ~PngEncoder();
    PngEncoder(const PngEncoder&) = delete;
    PngEncoder& operator=(const PngEncoder&) = delete;

    // The next `count` rows, format.rowBytes() each, the samples as the file stores them
    // (16-bit big-endian). Throws std::logic_error past the image's height.
    void addRows(const uint8_t* rows, uint32_t count);
    // After the last row: the rest of the image data and IEND. Throws std::logic_error if
    // rows are missing.
    void finish();

    // What became of the pieces so far, for tests and the bench.
    struct Statistics {
        size_t pieces = 0;
        size_t flat = 0;            // deflated by zlib
        size_t unfiltered = 0;      // stored unfiltered
        size_t deflated_again = 0;  // against the real dictionary, after the piece before chose otherwise
    };
    const Statistics& statistics() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

// Writes one chunk to `sink`: length, type, data and the CRC-32 of type and data.
void writePngChunk(const PngEncoder::Sink& sink, const char* type, const std::string& data);

}  // namespace ddt
