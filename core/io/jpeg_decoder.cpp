#include "jpeg_decoder.h"

// jpeglib.h needs FILE and size_t declared before it.
#include <jpeglib.h>

#include <cerrno>
#include <csetjmp>
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
    ErrorManager errors{};
    jpeg_decompress_struct info{};
    bool created = false;
    bool decoded = false;

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
    s.info.err = jpeg_std_error(&s.errors.base);
    s.errors.base.error_exit = failHere;
    s.errors.base.emit_message = onMessage;
    const bool ok = guarded(s.errors, [&] {
        jpeg_create_decompress(&s.info);
        s.created = true;
        jpeg_stdio_src(&s.info, s.file);
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

void JpegDecoder::decode(uint8_t* codes) {
    State& s = *state_;
    if (!decodable()) throw std::logic_error("JpegDecoder::decode: not a grey, YCbCr or RGB file");
    if (s.decoded) throw std::logic_error("JpegDecoder::decode called twice");
    s.decoded = true;
    const size_t row_bytes = size_t(width()) * channels();
    const bool ok = guarded(s.errors, [&] {
        jpeg_start_decompress(&s.info);
        while (s.info.output_scanline < s.info.output_height) {
            JSAMPROW row = codes + size_t(s.info.output_scanline) * row_bytes;
            jpeg_read_scanlines(&s.info, &row, 1);
        }
        jpeg_finish_decompress(&s.info);
    });
    if (!ok) throw UserError(s.name + ": truncated or corrupt image (" + s.errors.message + ")");
}

}  // namespace ddt
