#include "png_encoder.h"

#include <isa-l/igzip_lib.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <initializer_list>
#include <stdexcept>

#include "parallel.h"
#include "png_deflate.h"

// Choices, measured with bench/bench_png.cpp on ddtup's outputs (astronaut ×8: 4096² RGB;
// baboon ×4, camera and coins ×8 (grey), fruits ×4 at 16 bits, the drawings monkey,
// rocket_clipart ×4 and ladybug ×4 with alpha, noise ×1 and ×2), against `vips copy` (zlib
// level 6, unfiltered), in processor time (the threads' sum):
//
// - Filter: libpng's heuristic (PngFilter::Adaptive), once per piece (PieceAdaptive): the
//   filter whose output has the smallest sum of magnitudes over every 4th row of the piece,
//   for all its rows. Per row, the heuristic came within 5 % of the best single filter on every
//   image, while each single filter was 5 to 9 % behind the best on some image (Paeth on
//   astronaut, Average on monkey, Up on baboon); it cost 0.09 s more than a single filter on
//   astronaut ×8. Per piece, the files are within 0.5 % of per row (chelsea ×2 0.5 % larger,
//   baboon 0.2 %, ladybug 0.05 % smaller) and the encoder takes 5 to 15 % less processor time
//   (the e2e bench's photo ×4: 0.69 → 0.58 s).
// - Compressor: ISA-L at level 1. Level 2 was at most 0.2 % smaller and slower, level 3
//   larger and slower, level 0 15 % larger. Astronaut ×8 takes 0.20 s (zlib at level 6: 0.9 s
//   for the unfiltered rows alone) and gives 14.1 MB: 57 % of vips' 24.6 MB (OpenImageIO's
//   writer, libpng's heuristic and zlib level 6: 12.5 MB in 3.3 s).
// - Flat pieces: on drawings every ISA-L choice was 15 to 69 % larger than vips; zlib's deeper
//   match search wins there, and whether filtering helps depends on the drawing (unfiltered
//   was 3 % smaller on rocket_clipart, filtered 8 % on ladybug). So a piece whose filtered
//   bytes are at least 80 % zeros is "flat" and deflated by zlib both filtered and unfiltered,
//   the smaller kept: rocket_clipart ×4 takes 0.16 s and comes out 2 % under vips. Every piece
//   ISA-L compressed worse than vips had 80 % zeros or more; photographs have few flat pieces
//   (astronaut ×8: 1 of 196; camera ×8: 18 of 66).
// - Unfiltered too: a flat piece, or one that filtered and deflated keeps more than half its
//   size, is also deflated unfiltered, the smaller kept. On noise about mid-grey (ImageMagick's
//   Gaussian noise on grey, 1024² RGB) filtering made ISA-L's output 3.5 % larger than vips',
//   unfiltered 2 % smaller. Smooth pieces compress to a fifth or less, and filtering won on
//   every one of them; trying them all cost 0.075 s of 0.32 s on astronaut ×8 and 0.25 s of
//   0.57 s on the 6400 × 4448 photo (the e2e bench's job b), none of it kept.
// - Piece size: 256 KiB. 64 KiB pieces were 0.2 to 2.4 % larger, 1 MiB ones no smaller.

namespace ddt {

namespace {

// Deflate's window: the most history a back-reference reaches, so the most a dictionary holds.
constexpr size_t kWindow = 32 * 1024;

// PngFilter::PieceAdaptive weighs the filters on every kPieceFilterRowStep-th row of a piece.
constexpr uint32_t kPieceFilterRowStep = 4;

// A piece is flat when at least this share of its filtered bytes are zeros.
constexpr size_t kFlatZerosPercent = 80;
// Filtered and deflated, a piece above this share of its size is noise-like enough for its
// unfiltered rows to be tried too.
constexpr size_t kPoorlyCompressedPercent = 50;

// zlib's header for a deflate stream with a 32 KiB window; FLEVEL 1 says "fast" (RFC 1950).
constexpr uint8_t kZlibHeader[2] = {0x78, 0x5E};

void putBigEndian32(uint8_t* at, uint32_t value) {
    at[0] = uint8_t(value >> 24);
    at[1] = uint8_t(value >> 16);
    at[2] = uint8_t(value >> 8);
    at[3] = uint8_t(value);
}

struct Bytes {
    const uint8_t* data;
    size_t size;
};

// One chunk whose data is the concatenation of `parts`.
void writeChunkParts(const PngEncoder::Sink& sink, const char* type, std::initializer_list<Bytes> parts) {
    size_t size = 0;
    for (const Bytes& part : parts) size += part.size;
    if (size > 0x7FFFFFFF) throw std::length_error("a PNG chunk holds less than 2 GiB");
    uint8_t head[8];
    putBigEndian32(head, uint32_t(size));
    std::memcpy(head + 4, type, 4);
    uLong crc = crc32(0, head + 4, 4);
    for (const Bytes& part : parts) crc = crc32_z(crc, part.data, part.size);
    uint8_t tail[4];
    putBigEndian32(tail, uint32_t(crc));
    sink(head, sizeof head);
    for (const Bytes& part : parts)
        if (part.size) sink(part.data, part.size);
    sink(tail, sizeof tail);
}

uint8_t colourType(uint32_t channels) {
    static const uint8_t types[] = {0, 4, 2, 6};  // grey, grey + alpha, RGB, RGBA
    return types[channels - 1];
}

size_t countZeros(const uint8_t* bytes, size_t size) {
    size_t zeros = 0;
    for (size_t i = 0; i < size; ++i) zeros += bytes[i] == 0;
    return zeros;
}

// One chunk of rows on its way through filtering and deflating; the vectors are reused
// batch after batch.
struct Piece {
    uint32_t first_row = 0, end_row = 0;
    size_t size = 0;                   // the piece's bytes in the image data, filtered or not
    std::vector<uint8_t> filtered;     // with Options::filter
    std::vector<uint8_t> unfiltered;   // filter type 0 on every row
    bool flat = false;
    bool stores_unfiltered = false;    // the choice
    Deflater deflater = Deflater::Isal;
    std::vector<uint8_t> compressed;
    size_t compressed_size = 0;
    std::vector<uint8_t> other;        // the second form's try
    uint32_t adler = 1;                // of the stored bytes
    PieceDeflater deflater_state;

    const uint8_t* stored() const { return stores_unfiltered ? unfiltered.data() : filtered.data(); }
};

}  // namespace

struct PngEncoder::State {
    PngFormat format;
    Options options;
    Sink sink;
    size_t row_bytes = 0;
    size_t bpp = 0;
    uint32_t rows_per_piece = 0;
    uint32_t batch_rows = 0;
    std::vector<uint8_t> rows;  // the row before the batch (zeros above the image), then the batch
    uint32_t buffered = 0;      // rows in the batch
    uint32_t rows_added = 0;
    std::vector<Piece> pieces;
    std::vector<uint8_t> history;  // the image data's last bytes before the batch, up to kWindow
    uLong adler = 1;               // of the image data written so far
    bool started = false;          // the zlib header is written
    bool finished = false;
    Statistics statistics;

    uint8_t* row(uint32_t index) { return rows.data() + size_t(index + 1) * row_bytes; }

    // Rows [first, end) as stored unfiltered: a 0 before each row.
    void unfilteredRows(uint32_t first, uint32_t end, uint8_t* out) {
        for (uint32_t y = first; y < end; ++y, out += row_bytes + 1) {
            out[0] = 0;
            std::memcpy(out + 1, row(y), row_bytes);
        }
    }

    void filterPiece(Piece& piece) {
        const size_t stride = row_bytes + 1;
        piece.size = size_t(piece.end_row - piece.first_row) * stride;
        if (piece.filtered.size() < piece.size) piece.filtered.resize(piece.size);
        PngFilter filter = options.filter;
        if (filter == PngFilter::PieceAdaptive) {
            uint64_t costs[5] = {};
            for (uint32_t y = piece.first_row; y < piece.end_row; y += kPieceFilterRowStep)
                addFilterCosts(row(y), row(y) - row_bytes, row_bytes, bpp, costs);
            filter = cheapestFilter(costs);
        }
        for (uint32_t y = piece.first_row; y < piece.end_row; ++y)
            filterPngRow(filter, row(y), row(y) - row_bytes, row_bytes, bpp,
                         piece.filtered.data() + size_t(y - piece.first_row) * stride);
        piece.flat = options.zlib_for_flat && countZeros(piece.filtered.data(), piece.size) * 100 >= kFlatZerosPercent * piece.size;
        piece.stores_unfiltered = false;
        if (piece.unfiltered.size() < piece.size) piece.unfiltered.resize(piece.size);
        unfilteredRows(piece.first_row, piece.end_row, piece.unfiltered.data());
    }

    // The last bytes of `piece` as stored (up to kWindow): the dictionary of the one after it.
    static Bytes endOf(const Piece& piece) {
        const size_t size = std::min(piece.size, kWindow);
        return {piece.stored() + piece.size - size, size};
    }

    // The dictionary for piece p if the piece before stores its rows the way `unfiltered`
    // says: the bytes before p in the image data under that assumption. The first piece of a
    // batch follows what was written, whatever the assumption.
    Bytes dictionary(size_t p, bool unfiltered) {
        if (p == 0) return {history.data(), history.size()};
        const Piece& before = pieces[p - 1];
        const size_t size = std::min(before.size, kWindow);
        return {(unfiltered ? before.unfiltered : before.filtered).data() + before.size - size, size};
    }

    // Deflates `piece` as it is stored, with its deflater, after `dictionary`.
    void deflatePiece(Piece& piece, const Bytes& dictionary, bool last) {
        piece.compressed_size = piece.deflater_state.deflate(piece.deflater, options.isal_level, dictionary.data, dictionary.size,
                                                             piece.stored(), piece.size, last, piece.compressed);
    }

    // Chooses how piece p is stored and deflates it: filtered and unfiltered, by zlib if the
    // piece is flat, else by ISA-L; the smaller kept (ties: filtered). Each form is deflated
    // as if the piece before were stored the same way.
    void choose(size_t p, bool last) {
        Piece& piece = pieces[p];
        piece.deflater = piece.flat ? Deflater::Zlib : Deflater::Isal;
        deflatePiece(piece, dictionary(p, false), last);
        if (options.try_unfiltered && (piece.flat || piece.compressed_size * 100 > kPoorlyCompressedPercent * piece.size))
            tryUnfiltered(p, last);
        piece.adler = isal_adler32(1, piece.stored(), piece.size);
    }

    void tryUnfiltered(size_t p, bool last) {
        Piece& piece = pieces[p];
        const Bytes from = dictionary(p, true);
        const size_t size = piece.deflater_state.deflate(piece.deflater, options.isal_level, from.data, from.size,
                                                         piece.unfiltered.data(), piece.size, last, piece.other);
        if (size < piece.compressed_size) {
            piece.stores_unfiltered = true;
            piece.compressed.swap(piece.other);
            piece.compressed_size = size;
        }
    }

    // Filters and deflates the buffered rows in parallel and writes them as IDAT chunks. The
    // output depends on the pieces alone: each choice is made against the dictionary the
    // piece would have if the piece before were stored the same way; where it is not, the
    // piece is deflated again against the real one.
    void encodeBatch(bool last) {
        const uint32_t count = (buffered + rows_per_piece - 1) / rows_per_piece;
        for (uint32_t p = 0; p < count; ++p) {
            pieces[p].first_row = p * rows_per_piece;
            pieces[p].end_row = std::min(buffered, (p + 1) * rows_per_piece);
        }
        auto isLast = [&](size_t p) { return last && p + 1 == count; };
        parallelFor(count, 1, [&](size_t begin, size_t end) {
            for (size_t p = begin; p < end; ++p) filterPiece(pieces[p]);
        });
        parallelFor(count, 1, [&](size_t begin, size_t end) {
            for (size_t p = begin; p < end; ++p) choose(p, isLast(p));
        });
        std::vector<size_t> again;
        for (size_t p = 1; p < count; ++p)
            if (pieces[p].stores_unfiltered != pieces[p - 1].stores_unfiltered) again.push_back(p);
        parallelFor(again.size(), 1, [&](size_t begin, size_t end) {
            for (size_t i = begin; i < end; ++i) deflatePiece(pieces[again[i]], endOf(pieces[again[i] - 1]), isLast(again[i]));
        });
        statistics.pieces += count;
        statistics.deflated_again += again.size();
        for (uint32_t p = 0; p < count; ++p) {
            const Piece& piece = pieces[p];
            statistics.flat += piece.flat;
            statistics.unfiltered += piece.stores_unfiltered;
            adler = adler32_combine(adler, piece.adler, z_off_t(piece.size));
            uint8_t trailer[4];
            putBigEndian32(trailer, uint32_t(adler));
            writeChunkParts(sink, "IDAT",
                            {{kZlibHeader, started ? 0u : sizeof kZlibHeader},
                             {piece.compressed.data(), piece.compressed_size},
                             {trailer, isLast(p) ? sizeof trailer : 0u}});
            started = true;
        }
        const Bytes end = endOf(pieces[count - 1]);
        history.assign(end.data, end.data + end.size);
        std::memcpy(rows.data(), row(buffered - 1), row_bytes);
        buffered = 0;
    }
};

PngEncoder::PngEncoder(const PngFormat& format, const std::vector<PngChunk>& metadata, Sink sink)
    : PngEncoder(format, metadata, std::move(sink), Options()) {}

PngEncoder::PngEncoder(const PngFormat& format, const std::vector<PngChunk>& metadata, Sink sink, const Options& options)
    : state_(std::make_unique<State>()) {
    if (format.width < 1 || format.height < 1 || format.width > 0x7FFFFFFF || format.height > 0x7FFFFFFF)
        throw std::invalid_argument("a PNG is 1 to 2^31 - 1 pixels a side");
    if (format.channels < 1 || format.channels > 4) throw std::invalid_argument("a PNG has 1 to 4 channels");
    if (format.bit_depth != 8 && format.bit_depth != 16) throw std::invalid_argument("PNG samples are 8 or 16 bits here");
    // A piece, at least a row, must fit an IDAT chunk however badly it compresses.
    if (format.rowBytes() >= (size_t(1) << 30)) throw std::invalid_argument("PNG rows of 1 GiB or more");
    if (options.isal_level < ISAL_DEF_MIN_LEVEL || options.isal_level > ISAL_DEF_MAX_LEVEL)
        throw std::invalid_argument("ISA-L's levels are 0 to 3");
    State& s = *state_;
    s.format = format;
    s.options = options;
    s.sink = std::move(sink);
    s.row_bytes = format.rowBytes();
    s.bpp = format.channels * (format.bit_depth / 8);
    s.rows_per_piece = uint32_t(std::clamp<size_t>(options.chunk_bytes / (s.row_bytes + 1), 1, format.height));
    // Two pieces a thread even out pieces that deflate at different speeds.
    const size_t pieces_in_image = (size_t(format.height) + s.rows_per_piece - 1) / s.rows_per_piece;
    const uint32_t pieces = uint32_t(std::min<size_t>(2 * threadCount(), pieces_in_image));
    s.batch_rows = pieces * s.rows_per_piece;
    s.pieces.resize(pieces);
    s.rows.assign(size_t(s.batch_rows + 1) * s.row_bytes, 0);

    static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    s.sink(signature, sizeof signature);
    std::string header(13, '\0');
    putBigEndian32(reinterpret_cast<uint8_t*>(header.data()), format.width);
    putBigEndian32(reinterpret_cast<uint8_t*>(header.data()) + 4, format.height);
    header[8] = char(format.bit_depth);
    header[9] = char(colourType(format.channels));
    // header[10..12] stay 0: deflate, adaptive filtering (filter method 0), not interlaced.
    writePngChunk(s.sink, "IHDR", header);
    for (const PngChunk& chunk : metadata) {
        if (chunk.type.size() != 4) throw std::invalid_argument("a PNG chunk type has 4 letters");
        writePngChunk(s.sink, chunk.type.c_str(), chunk.data);
    }
}

PngEncoder::~PngEncoder() = default;

void PngEncoder::addRows(const uint8_t* rows, uint32_t count) {
    State& s = *state_;
    if (s.finished || count > s.format.height - s.rows_added) throw std::logic_error("PngEncoder: more rows than the image has");
    while (count > 0) {
        // A full batch is encoded only when more rows come, so that the last one is known.
        if (s.buffered == s.batch_rows) s.encodeBatch(false);
        const uint32_t taken = std::min(count, s.batch_rows - s.buffered);
        std::memcpy(s.row(s.buffered), rows, size_t(taken) * s.row_bytes);
        rows += size_t(taken) * s.row_bytes;
        s.buffered += taken;
        s.rows_added += taken;
        count -= taken;
    }
}

void PngEncoder::finish() {
    State& s = *state_;
    if (s.finished || s.rows_added != s.format.height) throw std::logic_error("PngEncoder: finished before the last row");
    s.encodeBatch(true);
    writePngChunk(s.sink, "IEND", "");
    s.finished = true;
}

const PngEncoder::Statistics& PngEncoder::statistics() const { return state_->statistics; }

void writePngChunk(const PngEncoder::Sink& sink, const char* type, const std::string& data) {
    writeChunkParts(sink, type, {{reinterpret_cast<const uint8_t*>(data.data()), data.size()}});
}

}  // namespace ddt
