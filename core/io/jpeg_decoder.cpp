#include "jpeg_decoder.h"

// jpeglib.h needs FILE and size_t declared before it.
#include <jpeglib.h>

#include <cerrno>
#include <csetjmp>
#include <cstdlib>
#include <cstring>
#include <map>
#include <stdexcept>

#include "jpeg_header.h"
#include "user_error.h"

namespace ddt {

namespace {

// How libjpeg reports to us: a fatal error jumps back to `guarded`, a warning (what a truncated
// or damaged file gets, with grey rows in place of the missing ones) is kept as a failure too.
struct ErrorManager {
    jpeg_error_mgr base;  // first, so that libjpeg's jpeg_error_mgr* is this
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
    bool failed;
};

ErrorManager& managerOf(j_common_ptr info) { return *reinterpret_cast<ErrorManager*>(info->err); }

// The first problem's text is the one the user gets.
void keepProblem(j_common_ptr info) {
    ErrorManager& errors = managerOf(info);
    if (!errors.failed) (*info->err->format_message)(info, errors.message);
    errors.failed = true;
}

[[noreturn]] void failHere(j_common_ptr info) {
    keepProblem(info);
    std::longjmp(managerOf(info).jump, 1);
}

// Level −1 is a warning; the others are traces, which stay silent.
void onMessage(j_common_ptr info, int level) {
    if (level < 0) keepProblem(info);
}

// `errors` set up to report to us, for a decompressor's or compressor's `err`.
jpeg_error_mgr* reportingTo(ErrorManager& errors) {
    jpeg_std_error(&errors.base);
    errors.base.error_exit = failHere;
    errors.base.emit_message = onMessage;
    return &errors.base;
}

// Runs `step`, which calls into libjpeg, and says whether libjpeg reported nothing. A fatal
// error comes back here by longjmp past `step`'s frames, which own nothing to destroy.
template <class Step>
bool guarded(ErrorManager& errors, const Step& step) {
    if (setjmp(errors.jump)) return false;
    step();
    return !errors.failed;
}

const int kExifMarker = JPEG_APP0 + 1;
const int kIccMarker = JPEG_APP0 + 2;
// The markers' names, NULs included ("Exif" and two, "ICC_PROFILE" and one), and the bytes
// before a chunk's data: an ICC chunk's name is followed by its number and the chunk count.
const char kExifName[] = "Exif\0";
const size_t kExifHeader = sizeof(kExifName);
const char kIccName[] = "ICC_PROFILE";
const size_t kIccHeader = sizeof(kIccName) + 2;

bool named(const jpeg_saved_marker_ptr marker, const char* name, size_t name_size, size_t header) {
    return marker->data_length >= header && std::memcmp(marker->data, name, name_size) == 0;
}

}  // namespace

// Frees libjpeg's state and closes the file also when the constructor throws.
struct JpegDecoder::State {
    std::string name;
    std::FILE* file = nullptr;
    std::vector<uint8_t> bytes;  // read instead of a file
    ErrorManager errors{};
    jpeg_decompress_struct info{};
    bool created = false;
    bool started = false;   // jpeg_start_decompress was called
    bool finished = false;  // and jpeg_finish_decompress

    ~State() {
        if (created) jpeg_destroy_decompress(&info);
        if (file) std::fclose(file);
    }
};

JpegDecoder::JpegDecoder(const std::string& path, const std::string& name) : state_(std::make_unique<State>()) {
    State& s = *state_;
    s.name = name;
    s.file = std::fopen(path.c_str(), "rb");
    if (!s.file) throw UserError(name + ": cannot open (" + std::strerror(errno) + ")");
    readHeader();
}

JpegDecoder::JpegDecoder(std::vector<uint8_t> bytes, const std::string& name) : state_(std::make_unique<State>()) {
    state_->name = name;
    state_->bytes = std::move(bytes);
    readHeader();
}

void JpegDecoder::readHeader() {
    State& s = *state_;
    const std::string& name = s.name;
    s.info.err = reportingTo(s.errors);
    const bool ok = guarded(s.errors, [&] {
        jpeg_create_decompress(&s.info);
        s.created = true;
        if (s.file) jpeg_stdio_src(&s.info, s.file);
        else jpeg_mem_src(&s.info, s.bytes.data(), s.bytes.size());
        keepMetadataMarkers(&s.info);
        jpeg_read_header(&s.info, TRUE);
    });
    if (!ok) throw UserError(name + ": not a readable JPEG image (" + s.errors.message + ")");

    std::map<int, std::vector<uint8_t>> icc_chunks;  // by chunk number
    for (jpeg_saved_marker_ptr marker = s.info.marker_list; marker; marker = marker->next) {
        if (marker->marker == kExifMarker && exif_.empty() && named(marker, kExifName, sizeof(kExifName), kExifHeader))
            exif_.assign(marker->data + kExifHeader, marker->data + marker->data_length);
        if (marker->marker == kIccMarker && named(marker, kIccName, sizeof(kIccName), kIccHeader))
            icc_chunks[marker->data[sizeof(kIccName)]].assign(marker->data + kIccHeader, marker->data + marker->data_length);
    }
    for (const auto& [number, chunk] : icc_chunks) icc_.insert(icc_.end(), chunk.begin(), chunk.end());
}

JpegDecoder::~JpegDecoder() = default;

uint32_t JpegDecoder::width() const { return state_->info.image_width; }
uint32_t JpegDecoder::height() const { return state_->info.image_height; }
uint32_t JpegDecoder::channels() const { return state_->info.jpeg_color_space == JCS_GRAYSCALE ? 1 : 3; }

bool JpegDecoder::decodable() const {
    const J_COLOR_SPACE space = state_->info.jpeg_color_space;
    return space == JCS_GRAYSCALE || space == JCS_YCbCr || space == JCS_RGB;
}

std::optional<ImageAttributes> JpegDecoder::attributes(const DecodeExif& decode_exif) const {
    return jpegAttributes(state_->info, decode_exif);
}

void JpegDecoder::check() {
    std::vector<uint8_t> row(size_t(width()) * channels());
    for (uint32_t y = 0; y < height(); ++y) decodeRows(1, row.data());
}

bool JpegDecoder::progressive() const { return jpeg_has_multiple_scans(&state_->info); }

std::unique_ptr<JpegDecoder> JpegDecoder::sequential() {
    State& s = *state_;
    if (s.started) throw std::logic_error("JpegDecoder::sequential after decoding began");
    s.started = true;
    jvirt_barray_ptr* coefficients = nullptr;
    if (!guarded(s.errors, [&] { coefficients = jpeg_read_coefficients(&s.info); }))
        throw UserError(s.name + ": truncated or corrupt image (" + s.errors.message + ")");

    ErrorManager errors{};
    jpeg_compress_struct out{};
    out.err = reportingTo(errors);
    unsigned char* buffer = nullptr;  // libjpeg's, from malloc
    unsigned long size = 0;
    bool created = false;
    const bool written = guarded(errors, [&] {
        jpeg_create_compress(&out);
        created = true;
        jpeg_mem_dest(&out, &buffer, &size);
        jpeg_copy_critical_parameters(&s.info, &out);
        out.optimize_coding = TRUE;
        jpeg_write_coefficients(&out, coefficients);
        jpeg_finish_compress(&out);
    });
    std::vector<uint8_t> bytes;
    if (written) bytes.assign(buffer, buffer + size);
    if (created) jpeg_destroy_compress(&out);
    std::free(buffer);
    if (!written) throw std::runtime_error(s.name + ": libjpeg could not store the coefficients again (" + errors.message + ")");
    const bool finished = guarded(s.errors, [&] { jpeg_finish_decompress(&s.info); });
    s.finished = true;
    if (!finished) throw UserError(s.name + ": truncated or corrupt image (" + s.errors.message + ")");
    return std::make_unique<JpegDecoder>(std::move(bytes), s.name);
}

void JpegDecoder::decode(uint8_t* codes) {
    if (state_->started) throw std::logic_error("JpegDecoder::decode called after other rows");
    decodeRows(height(), codes);
}

void JpegDecoder::decodeRows(uint32_t count, uint8_t* codes) {
    State& s = *state_;
    if (!decodable()) throw std::logic_error("JpegDecoder::decode: not a grey, YCbCr or RGB file");
    if (s.finished || count > height() - s.info.output_scanline)
        throw std::logic_error("JpegDecoder: rows asked beyond the image");
    const size_t row_bytes = size_t(width()) * channels();
    const uint32_t end = s.info.output_scanline + count;
    const bool ok = guarded(s.errors, [&] {
        if (!s.started) jpeg_start_decompress(&s.info);
        s.started = true;
        while (s.info.output_scanline < end) {
            JSAMPROW row = codes + size_t(count - (end - s.info.output_scanline)) * row_bytes;
            jpeg_read_scanlines(&s.info, &row, 1);
        }
        if (s.info.output_scanline == s.info.output_height) {
            jpeg_finish_decompress(&s.info);
            s.finished = true;
        }
    });
    if (!ok) throw UserError(s.name + ": truncated or corrupt image (" + s.errors.message + ")");
}

}  // namespace ddt
