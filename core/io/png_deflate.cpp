#include "png_deflate.h"

#include <isa-l/igzip_lib.h>
#include <zlib.h>

#include <stdexcept>
#include <utility>

namespace ddt {

namespace {

// ISA-L's memory for each level: its suggested default sizes.
size_t isalLevelBufferSize(int level) {
    switch (level) {
        case 1:
            return ISAL_DEF_LVL1_DEFAULT;
        case 2:
            return ISAL_DEF_LVL2_DEFAULT;
        case 3:
            return ISAL_DEF_LVL3_DEFAULT;
        default:
            return ISAL_DEF_LVL0_DEFAULT;
    }
}

// Calls `step(to, room)`, one call of a compressor writing at most `room` bytes at `to` that
// returns the room it left and whether it is done, until it is done, growing `out` as needed
// (incompressible data grows by a few bytes a block). Returns the bytes written.
template <class Step>
size_t compressInto(std::vector<uint8_t>& out, size_t input_size, Step step) {
    const size_t room = input_size + input_size / 64 + 1024;
    if (out.size() < room) out.resize(room);
    size_t produced = 0;
    for (;;) {
        const auto [left, done] = step(out.data() + produced, out.size() - produced);
        produced = out.size() - left;
        if (done) return produced;
        out.resize(out.size() * 2);
    }
}

}  // namespace

struct PieceDeflater::State {
    std::unique_ptr<isal_zstream> isal;
    std::vector<uint8_t> isal_level_buffer;
    z_stream zlib{};
    bool zlib_ready = false;

    ~State() {
        if (zlib_ready) deflateEnd(&zlib);
    }

    size_t deflateIsal(int level, const uint8_t* dictionary, size_t dictionary_size, const uint8_t* in, size_t size, bool last,
                       std::vector<uint8_t>& out) {
        if (!isal) isal = std::make_unique<isal_zstream>();
        isal_level_buffer.resize(isalLevelBufferSize(level));
        isal_zstream& z = *isal;
        isal_deflate_init(&z);
        z.level = uint32_t(level);
        z.level_buf = isal_level_buffer.empty() ? nullptr : isal_level_buffer.data();
        z.level_buf_size = uint32_t(isal_level_buffer.size());
        z.gzip_flag = IGZIP_DEFLATE;
        z.flush = SYNC_FLUSH;
        z.end_of_stream = last ? 1 : 0;
        if (dictionary_size && isal_deflate_set_dict(&z, const_cast<uint8_t*>(dictionary), uint32_t(dictionary_size)) != COMP_OK)
            throw std::runtime_error("ISA-L refused a deflate dictionary");
        z.next_in = const_cast<uint8_t*>(in);
        z.avail_in = uint32_t(size);
        return compressInto(out, size, [&](uint8_t* to, size_t room) {
            z.next_out = to;
            z.avail_out = uint32_t(room);
            if (isal_deflate(&z) != COMP_OK) throw std::runtime_error("ISA-L's deflate failed");
            // Input all taken and room left over: the flush, or the final block, is complete.
            const bool done = z.avail_in == 0 && z.avail_out > 0 && (!last || z.internal_state.state == ZSTATE_END);
            return std::pair{size_t(z.avail_out), done};
        });
    }

    // zlib's level 6 with the lazy and "nice" match lengths of level 9 (258): 1 % smaller
    // than plain level 6 on drawings, in the same time (measured on ddtup's ×4 outputs of
    // bench/data/artificial); level 9's longer chains cost 5 times the time.
    size_t deflateZlib(const uint8_t* dictionary, size_t dictionary_size, const uint8_t* in, size_t size, bool last,
                       std::vector<uint8_t>& out) {
        if (!zlib_ready) {
            if (deflateInit2(&zlib, 6, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) throw std::bad_alloc();
            zlib_ready = true;
        } else if (deflateReset(&zlib) != Z_OK) {
            throw std::runtime_error("zlib's deflateReset failed");
        }
        deflateTune(&zlib, 8, 258, 258, 128);  // after each reset, which restores level 6's values
        if (dictionary_size && deflateSetDictionary(&zlib, dictionary, uInt(dictionary_size)) != Z_OK)
            throw std::runtime_error("zlib refused a deflate dictionary");
        zlib.next_in = const_cast<Bytef*>(in);
        zlib.avail_in = uInt(size);
        return compressInto(out, size, [&](uint8_t* to, size_t room) {
            zlib.next_out = to;
            zlib.avail_out = uInt(room);
            const int result = ::deflate(&zlib, last ? Z_FINISH : Z_SYNC_FLUSH);
            if (result == Z_STREAM_ERROR) throw std::runtime_error("zlib's deflate failed");
            // As for ISA-L: done when deflate left room, or when it says the stream ended.
            const bool done = last ? result == Z_STREAM_END : zlib.avail_in == 0 && zlib.avail_out > 0;
            return std::pair{size_t(zlib.avail_out), done};
        });
    }
};

PieceDeflater::PieceDeflater() : state_(std::make_unique<State>()) {}

PieceDeflater::~PieceDeflater() = default;
PieceDeflater::PieceDeflater(PieceDeflater&&) noexcept = default;
PieceDeflater& PieceDeflater::operator=(PieceDeflater&&) noexcept = default;

size_t PieceDeflater::deflate(Deflater deflater, int isal_level, const uint8_t* dictionary, size_t dictionary_size,
                              const uint8_t* in, size_t size, bool last, std::vector<uint8_t>& out) {
    if (deflater == Deflater::Isal) return state_->deflateIsal(isal_level, dictionary, dictionary_size, in, size, last, out);
    return state_->deflateZlib(dictionary, dictionary_size, in, size, last, out);
}

}  // namespace ddt
