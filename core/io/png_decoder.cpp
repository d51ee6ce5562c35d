#include "png_decoder.h"

#include <spng.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "user_error.h"

namespace ddt {

namespace {

// libspng's output format and flags for a file, and the layout they give.
struct Output {
    int format;
    int flags;
    uint32_t channels, bits;
};

// As OpenImageIO 2.4's PNG reader sets up libpng: palettes to RGB, grey below 8 bits to 8,
// tRNS to an alpha channel, 16-bit samples in host order, nothing else.
Output outputFor(const spng_ihdr& header, bool transparency) {
    const bool wide = header.bit_depth == 16;
    switch (header.color_type) {
    case SPNG_COLOR_TYPE_GRAYSCALE:
        if (transparency) return wide ? Output{SPNG_FMT_GA16, SPNG_DECODE_TRNS, 2, 16} : Output{SPNG_FMT_GA8, SPNG_DECODE_TRNS, 2, 8};
        return wide ? Output{SPNG_FMT_PNG, 0, 1, 16} : Output{SPNG_FMT_G8, 0, 1, 8};
    case SPNG_COLOR_TYPE_TRUECOLOR:
        if (transparency) return wide ? Output{SPNG_FMT_RGBA16, SPNG_DECODE_TRNS, 4, 16} : Output{SPNG_FMT_RGBA8, SPNG_DECODE_TRNS, 4, 8};
        return {SPNG_FMT_PNG, 0, 3, wide ? 16u : 8u};
    case SPNG_COLOR_TYPE_INDEXED:
        return transparency ? Output{SPNG_FMT_RGBA8, SPNG_DECODE_TRNS, 4, 8} : Output{SPNG_FMT_RGB8, 0, 3, 8};
    case SPNG_COLOR_TYPE_GRAYSCALE_ALPHA: return {SPNG_FMT_PNG, 0, 2, wide ? 16u : 8u};
    default: return {SPNG_FMT_PNG, 0, 4, wide ? 16u : 8u};  // truecolour with alpha
    }
}

}  // namespace

// Frees libspng's context and closes the file also when the constructor throws.
struct PngDecoder::State {
    std::string name;
    std::FILE* file = nullptr;
    spng_ctx* context = nullptr;
    spng_ihdr header{};
    Output output{};
    bool decoded = false;
    uint32_t rows_decoded = 0;  // by decodeRows

    ~State() {
        spng_ctx_free(context);
        if (file) std::fclose(file);
    }
};

PngDecoder::PngDecoder(const std::string& path, const std::string& name) : state_(std::make_unique<State>()) {
    State& s = *state_;
    s.name = name;
    s.file = std::fopen(path.c_str(), "rb");
    if (!s.file) throw UserError(name + ": cannot open (" + std::strerror(errno) + ")");
    s.context = spng_ctx_new(0);
    if (!s.context) throw std::bad_alloc();
    int error = spng_set_png_file(s.context, s.file);
    if (!error) error = spng_get_ihdr(s.context, &s.header);
    if (error) throw UserError(name + ": not a readable PNG image (" + spng_strerror(error) + ")");
    spng_trns transparency;
    s.output = outputFor(s.header, spng_get_trns(s.context, &transparency) == 0);
}

PngDecoder::~PngDecoder() = default;

uint32_t PngDecoder::width() const { return state_->header.width; }
uint32_t PngDecoder::height() const { return state_->header.height; }
uint32_t PngDecoder::channels() const { return state_->output.channels; }
uint32_t PngDecoder::sampleBits() const { return state_->output.bits; }

void PngDecoder::decode(void* samples) {
    State& s = *state_;
    if (s.decoded || s.rows_decoded) throw std::logic_error("PngDecoder::decode called twice");
    s.decoded = true;
    size_t size = 0;
    int error = spng_decoded_image_size(s.context, s.output.format, &size);
    if (!error && size != size_t(width()) * height() * channels() * (sampleBits() / 8))
        throw std::logic_error(s.name + ": libspng's image size is not the layout's");
    if (!error) error = spng_decode_image(s.context, samples, size, s.output.format, s.output.flags);
    // libspng stops reading the image data once it has every row: the rest of the stream, its
    // Adler-32 and the chunks' CRCs are checked only by reading on to the end, as libpng does.
    if (!error) error = spng_decode_chunks(s.context);
    if (error) throw UserError(s.name + ": truncated or corrupt image (" + spng_strerror(error) + ")");
}

bool PngDecoder::interlaced() const { return state_->header.interlace_method != SPNG_INTERLACE_NONE; }

void PngDecoder::decodeRows(uint32_t count, void* samples) {
    State& s = *state_;
    if (s.decoded || interlaced() || count > height() - s.rows_decoded)
        throw std::logic_error("PngDecoder: rows asked beyond the image or out of order");
    const size_t row_bytes = size_t(width()) * channels() * (sampleBits() / 8);
    int error = 0;
    if (s.rows_decoded == 0 && count > 0)
        error = spng_decode_image(s.context, nullptr, 0, s.output.format, s.output.flags | SPNG_DECODE_PROGRESSIVE);
    auto* rows = static_cast<uint8_t*>(samples);
    for (uint32_t i = 0; i < count && !error; ++i) {
        error = spng_decode_row(s.context, rows + i * row_bytes, row_bytes);
        ++s.rows_decoded;
        if (error == SPNG_EOI && s.rows_decoded == height()) error = 0;  // the last row
    }
    // As decode(): the rest of the stream and the CRCs are checked by reading on to the end.
    if (!error && count > 0 && s.rows_decoded == height()) {
        s.decoded = true;
        error = spng_decode_chunks(s.context);
    }
    if (error) throw UserError(s.name + ": truncated or corrupt image (" + spng_strerror(error) + ")");
}

void PngDecoder::check() {
    std::vector<uint8_t> row(size_t(width()) * channels() * (sampleBits() / 8));
    for (uint32_t y = 0; y < height(); ++y) decodeRows(1, row.data());
}

std::vector<uint8_t> PngDecoder::exif() const {
    spng_exif exif{};
    if (spng_get_exif(state_->context, &exif) != 0) return {};
    return std::vector<uint8_t>(exif.data, exif.data + exif.length);
}

std::vector<uint8_t> PngDecoder::iccProfile() const {
    spng_iccp profile{};
    if (spng_get_iccp(state_->context, &profile) != 0) return {};
    return std::vector<uint8_t>(profile.profile, profile.profile + profile.profile_len);
}

}  // namespace ddt
