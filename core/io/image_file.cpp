#include "image_file.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cassert>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <new>
#include <set>
#include <system_error>

#include "checked_file.h"
#include "image_formats.h"
#include "input_check.h"
#include "parallel.h"
#include "output_file.h"
#include "png_writer.h"
#include "temp_files.h"

namespace ddt {

// How a file keeps colour under alpha.
enum class AlphaStorage { Straight, Premultiplied };

struct ImageMetadata {
    OIIO::ImageSpec spec;        // the input's spec: its extra attributes are copied to the output
    std::string format_name;     // OIIO's name of the input's format ("png", "openexr", …)
    AlphaStorage alpha_storage;  // how the input file stored colour under alpha
};

namespace {

namespace fs = std::filesystem;

// OIIO messages can span lines; the user gets one.
std::string firstLine(std::string message) {
    size_t end = message.find('\n');
    if (end != std::string::npos) message.resize(end);
    while (!message.empty() && (message.back() == ' ' || message.back() == '.')) message.pop_back();
    return message.empty() ? "unknown error" : message;
}

// OIIO's per-thread error, for failures that have no ImageInput/ImageOutput to ask.
std::string globalError() { return OIIO::has_error() ? OIIO::geterror() : std::string(); }

template <class Codec>
std::string codecError(const Codec& codec) {
    return codec.has_error() ? codec.geterror() : globalError();
}

// OIIO 2.4's PNG plugin leaves libpng's default handlers installed, and they print
// "libpng error: …" (and warnings) to stderr on top of the error OIIO returns to us; newer OIIO
// installs its own handlers, 2.4 has no hook for them. The user must get one line, so stderr
// points at /dev/null for the duration of each call into a codec, and only then. Batches read
// and write on two threads at once: the first to enter redirects, the last to leave restores.
class QuietStderr {
public:
    QuietStderr() {
        std::lock_guard lock(mutex_);
        if (users_++ > 0) return;
        std::fflush(stderr);
        int null_fd = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
        if (null_fd < 0) return;
        saved_fd_ = ::fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 0);
        if (saved_fd_ >= 0) ::dup2(null_fd, STDERR_FILENO);
        ::close(null_fd);
    }
    ~QuietStderr() {
        std::lock_guard lock(mutex_);
        if (--users_ > 0 || saved_fd_ < 0) return;
        std::fflush(stderr);
        ::dup2(saved_fd_, STDERR_FILENO);
        ::close(saved_fd_);
        saved_fd_ = -1;
    }
    QuietStderr(const QuietStderr&) = delete;
    QuietStderr& operator=(const QuietStderr&) = delete;

private:
    static inline std::mutex mutex_;
    static inline int users_ = 0;
    static inline int saved_fd_ = -1;
};

SampleType sampleTypeOf(OIIO::TypeDesc format) {
    switch (format.basetype) {
        case OIIO::TypeDesc::UINT8:
        case OIIO::TypeDesc::INT8:
            return SampleType::UInt8;
        case OIIO::TypeDesc::UINT16:
        case OIIO::TypeDesc::INT16:
            return SampleType::UInt16;
        case OIIO::TypeDesc::HALF:
            return SampleType::Half;
        default:
            return SampleType::Float;
    }
}

OIIO::TypeDesc typeDescOf(SampleType type) {
    switch (type) {
        case SampleType::UInt8:
            return OIIO::TypeDesc::UINT8;
        case SampleType::UInt16:
            return OIIO::TypeDesc::UINT16;
        case SampleType::Half:
            return OIIO::TypeDesc::HALF;
        case SampleType::Float:
            break;
    }
    return OIIO::TypeDesc::FLOAT;
}

// ---- Alpha: what OIIO 2.4 actually does, measured per format (see test_image_io.cpp).
// Asked with "oiio:UnassociatedAlpha", the PNG, Targa and TIFF (unassociated) readers return
// straight colour and say so in that attribute. The BMP reader returns its straight colour as
// stored without saying so. OpenEXR and associated TIFF come back as stored, premultiplied,
// which is also OIIO's convention for every other reader.
AlphaStorage inputAlphaStorage(const OIIO::ImageSpec& spec, const std::string& format) {
    if (spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0) return AlphaStorage::Straight;
    if (format == "bmp") return AlphaStorage::Straight;
    return AlphaStorage::Premultiplied;
}

// Formats whose files hold straight colour: the PNG, Targa and WebP writers store straight
// colour given with "oiio:UnassociatedAlpha" as is (without it they divide by alpha after
// rounding to the file's depth, which loses precision); the BMP writer stores whatever it
// gets. TIFF can hold either and keeps the input's choice, so -s 1 reproduces it. Every other
// format gets premultiplied colour: OpenEXR requires it, and it is OIIO's convention for
// formats that do not say.
AlphaStorage outputAlphaStorage(const std::string& format, const Image& like) {
    static const std::set<std::string> straight = {"png", "targa", "webp", "bmp"};
    if (format == "tiff") return like.metadata ? like.metadata->alpha_storage : AlphaStorage::Straight;
    return straight.count(format) ? AlphaStorage::Straight : AlphaStorage::Premultiplied;
}

void premultiply(std::vector<float>& pixels, uint32_t channels) {
    for (size_t i = 0; i < pixels.size(); i += channels) {
        float alpha = pixels[i + channels - 1];
        for (uint32_t k = 0; k + 1 < channels; ++k) pixels[i + k] *= alpha;
    }
}

// ---- Reading.

std::string channelList(const OIIO::ImageSpec& spec) {
    std::string list;
    for (int c = 0; c < spec.nchannels; ++c) {
        if (c) list += ", ";
        list += spec.channel_name(c);
    }
    return list;
}

// "" for grey, grey+alpha, RGB or RGBA with alpha last, else the reason.
std::string checkChannelLayout(const OIIO::ImageSpec& spec) {
    const int n = spec.nchannels;
    const bool valid_alpha = spec.alpha_channel >= 0 && spec.alpha_channel < n;
    // OIIO 2.4's GIF reader reports alpha_channel = 4 for its R, G, B, A: trust the name too.
    const bool alpha_last = spec.alpha_channel == n - 1 || (!valid_alpha && n > 0 && spec.channel_name(n - 1) == "A");
    const bool ok = (n == 1 || n == 3) ? !valid_alpha : (n == 2 || n == 4) && alpha_last;
    if (ok) return "";
    return std::to_string(n) + " channels (" + channelList(spec) +
           "); ddtup reads grey, grey+alpha, RGB or RGBA images with alpha last";
}

}  // namespace


namespace {

// Codecs seek, and a pipe cannot: standard input is copied to a temporary file first.
std::unique_ptr<TempFile> copyStandardInput() {
    const std::string folder = tempFolder();
    auto fail = [&](int error) {
        return UserError("standard input: cannot copy it to a temporary file in " + folder + " (" + std::strerror(error) + ")");
    };
    std::unique_ptr<TempFile> copy;
    try {
        copy = std::make_unique<TempFile>(folder, "ddtup-stdin");
    } catch (const std::system_error& error) {
        throw fail(error.code().value());
    }
    CheckedFile file(copy->path());
    const CopyFailure failure = copyAll(STDIN_FILENO, [&](const char* data, size_t size) {
        return file.write(data, size) == size ? 0 : file.failure();
    });
    if (failure.read_error)
        throw UserError(std::string("standard input: cannot read it (") + std::strerror(failure.read_error) + ")");
    file.close();
    if (file.failure()) throw fail(file.failure());
    return copy;
}

// "" if `path` names a readable regular file, else the reason.
std::string checkInputFile(const std::string& path) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) return "no such file";
    if (fs::is_directory(status)) return "is a folder, not an image file";
    // Devices and pipes can feed a reader forever (/dev/zero) or block it.
    if (!fs::is_regular_file(status)) return "not a regular file";
    if (::access(path.c_str(), R_OK) != 0) return std::string("cannot open (") + std::strerror(errno) + ")";
    return "";
}

// Whether the file holds a second image (a page, a frame; MIP levels do not count). Only
// one seek: counting them all decodes every frame of an animated GIF (0.85 s for 300 frames
// of 512², measured), for a note.
bool hasSeveralImages(OIIO::ImageInput& input) {
    // OIIO 2.4's WebP reader loses its frame when a seek fails (libwebp clears the iterator,
    // and the seek back to 0 finds the reader already there), and a still image then fails
    // to decode. Only animations hold more than one image, and its spec says which are.
    if (input.format_name() == std::string("webp")) return input.spec().get_int_attribute("oiio:Movie") != 0;
    const bool several = input.seek_subimage(1, 0);
    input.seek_subimage(0, 0);
    globalError();  // a failed seek past the last image leaves a message
    codecError(input);
    return several;
}

// EXIF orientation 5..8 turn the stored image a quarter: the upright size is the stored size swapped.
bool swapsSides(int orientation) { return orientation >= 5 && orientation <= 8; }

// Turns and mirrors the pixels as EXIF orientation 2..8 asks, so that they are upright.
// Not ImageBufAlgo::reorient: OIIO 2.4 swaps 5 and 7 there (OpenImageIO issue #4661).
void makeUpright(Image& image, int orientation) {
    namespace iba = OIIO::ImageBufAlgo;
    const bool swapped = swapsSides(orientation);
    const OIIO::ImageSpec stored_spec(int(swapped ? image.height : image.width), int(swapped ? image.width : image.height),
                                      int(image.channels), OIIO::TypeDesc::FLOAT);
    const OIIO::ImageBuf stored(stored_spec, image.pixels.data());
    OIIO::ImageBuf upright, half_turned;
    bool ok = false;
    switch (orientation) {
        case 2: ok = iba::flop(upright, stored); break;        // mirrored left to right
        case 3: ok = iba::rotate180(upright, stored); break;
        case 4: ok = iba::flip(upright, stored); break;        // mirrored top to bottom
        case 5: ok = iba::transpose(upright, stored); break;   // mirrored across the main diagonal
        case 6: ok = iba::rotate90(upright, stored); break;    // clockwise
        case 7: ok = iba::rotate180(half_turned, stored) && iba::transpose(upright, half_turned); break;
        case 8: ok = iba::rotate270(upright, stored); break;
    }
    if (!ok) throw std::runtime_error("orienting the image: " + upright.geterror());
    upright.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, image.pixels.data());
}

// Rows decoded per call, a whole number of TIFF strips. OIIO 2.4's TIFF reader goes on through
// every strip of a call after one fails, adding a message each (and then reports success),
// and ends the process when its messages pass 16 MB: a damaged TIFF claiming 65536 rows of 3
// planes did (found by the fuzzer). In bands of about 1024 rows, stopping at the first band
// with an error, that cannot happen.
int decodeBandRows(const OIIO::ImageSpec& spec) {
    const int rows_per_strip = spec.get_int_attribute("tiff:RowsPerStrip", 64);
    if (rows_per_strip <= 0 || rows_per_strip >= spec.height) return spec.height;
    return std::min(spec.height, (1023 / rows_per_strip + 1) * rows_per_strip);
}

// Decodes the current image as floats, its channels interleaved; tiled files as OIIO does.
bool decodePixels(OIIO::ImageInput& input, float* pixels) {
    const OIIO::ImageSpec& spec = input.spec();
    if (spec.tile_width) return input.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels);
    const int band = decodeBandRows(spec);
    const size_t row_floats = size_t(spec.width) * spec.nchannels;
    for (int y = 0; y < spec.height; y += band) {
        const int end = std::min(spec.height, y + band);
        if (!input.read_scanlines(0, 0, spec.y + y, spec.y + end, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT,
                                  pixels + size_t(y) * row_floats) ||
            input.has_error())
            return false;
    }
    return true;
}

bool allFinite(const std::vector<float>& pixels) {
    for (float value : pixels)
        if (!std::isfinite(value)) return false;
    return true;
}

}  // namespace

struct ImageReader::State {
    std::string name;                      // for messages: the path, or "standard input"
    std::unique_ptr<TempFile> stdin_copy;  // what is read when the path is "-"
    std::unique_ptr<OIIO::ImageInput> input;
    AlphaStorage alpha_storage = AlphaStorage::Premultiplied;
    int orientation = 1;
};

ImageReader::ImageReader(const std::string& path) : state_(std::make_unique<State>()) {
    State& s = *state_;
    s.name = inputName(path);
    std::string file = path;
    if (path == kStandardStream) {
        s.stdin_copy = copyStandardInput();
        file = s.stdin_copy->path();
    } else if (std::string problem = checkInputFile(path); !problem.empty()) {
        throw UserError(s.name + ": " + problem);
    }
    std::error_code ec;
    if (fs::file_size(file, ec) == 0 && !ec) throw UserError(s.name + ": empty file (0 bytes)");

    // Only the reader of the file's own format, one of ours, sees it: OIIO's open() would try
    // every reader it has (image_formats.h). The content decides, so a mis-named file or the
    // extension-less copy of standard input is recognised.
    const ImageFormat* format = formatOfContent(file, s.stdin_copy ? std::string() : path);
    if (!format)
        throw UserError(s.name + ": not an image in a format ddtup reads (" + imageFormatTitles() + ")");
    if (std::string problem = checkBeforeDecoding(file, format->oiio_name); !problem.empty())
        throw UserError(s.name + ": " + problem);
    // Ask readers for straight alpha as stored; premultiplying in float loses nothing.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    {
        QuietStderr quiet;
        s.input = OIIO::ImageInput::create(format->oiio_name);
        OIIO::ImageSpec opened;
        if (s.input && !s.input->open(file, opened, config)) {
            const std::string reason = firstLine(codecError(*s.input));
            throw UserError(s.name + ": not a readable " + format->title + " image (" + reason + ")");
        }
    }
    if (!s.input) throw std::runtime_error(std::string("OpenImageIO has no ") + format->title + " reader");

    bool several;
    {
        QuietStderr quiet;
        several = hasSeveralImages(*s.input);
    }
    if (several) notes_.push_back(s.name + ": has more than one image (pages or frames); using the first");
    const OIIO::ImageSpec& spec = s.input->spec();
    if (spec.deep) throw UserError(s.name + ": deep images are not supported");
    if (spec.depth > 1) throw UserError(s.name + ": volume images are not supported");
    if (spec.width < 1 || spec.height < 1) throw UserError(s.name + ": the image has no pixels");
    if (uint64_t(spec.width) * uint64_t(spec.height) > kMaxInputPixels)
        throw UserError(s.name + ": image is " + std::to_string(spec.width) + "×" + std::to_string(spec.height) +
                        " pixels; ddtup reads at most " + std::to_string(kMaxInputPixels) + " pixels (16384×16384)");
    if (std::string problem = checkChannelLayout(spec); !problem.empty()) throw UserError(s.name + ": " + problem);

    const int orientation = spec.get_int_attribute("Orientation", 1);
    if (orientation >= 2 && orientation <= 8) s.orientation = orientation;
    const bool swapped = swapsSides(s.orientation);

    auto metadata = std::make_shared<ImageMetadata>();
    metadata->spec = spec;
    metadata->format_name = s.input->format_name();
    metadata->alpha_storage = inputAlphaStorage(spec, metadata->format_name);
    // The metadata describes the upright image the reader returns.
    metadata->spec.erase_attribute("Orientation");
    if (swapped) {
        const float x_resolution = spec.get_float_attribute("XResolution", 0.0f);
        const float y_resolution = spec.get_float_attribute("YResolution", 0.0f);
        if (x_resolution > 0.0f && y_resolution > 0.0f) {
            metadata->spec.attribute("XResolution", y_resolution);
            metadata->spec.attribute("YResolution", x_resolution);
        }
    }
    s.alpha_storage = metadata->alpha_storage;

    header_.width = uint32_t(swapped ? spec.height : spec.width);
    header_.height = uint32_t(swapped ? spec.width : spec.height);
    header_.channels = uint32_t(spec.nchannels);
    header_.sample_type = sampleTypeOf(spec.format);
    header_.metadata = metadata;
}

ImageReader::~ImageReader() = default;

Image ImageReader::read() {
    State& s = *state_;
    if (!s.input) throw std::logic_error("ImageReader::read called twice");
    Image image = header_;
    try {
        image.pixels.resize(size_t(image.width) * image.height * image.channels);
    } catch (const std::bad_alloc&) {
        throw UserError(s.name + ": too large to hold in memory (" + std::to_string(image.width) + "×" +
                        std::to_string(image.height) + ")");
    }
    bool ok;
    {
        QuietStderr quiet;
        ok = decodePixels(*s.input, image.pixels.data());
    }
    // libjpeg fills a truncated file with grey and OIIO returns success, but records the error.
    if (!ok || s.input->has_error())
        throw UserError(s.name + ": truncated or corrupt image (" + firstLine(codecError(*s.input)) + ")");
    s.input.reset();
    s.stdin_copy.reset();
    // Interpolating across a NaN or an infinity spreads it over the whole neighbourhood.
    if ((image.sample_type == SampleType::Half || image.sample_type == SampleType::Float) && !allFinite(image.pixels))
        throw UserError(s.name + ": contains NaN or infinite values");
    if (s.orientation != 1) makeUpright(image, s.orientation);
    if (image.hasAlpha() && s.alpha_storage == AlphaStorage::Straight) premultiply(image.pixels, image.channels);
    return image;
}

Image readImage(const std::string& path) { return ImageReader(path).read(); }

// ---- Writing.

namespace {

// The largest side a format can hold, for the formats where OIIO 2.4 does not refuse a larger
// one cleanly when the output is opened (measured): libjpeg ends the whole process, libpng
// prints its own error, GIF files come out corrupt, WebP fails only after all the work.
struct SideLimit {
    const char* format;
    uint32_t max_side;
};
const SideLimit kSideLimits[] = {
    {"jpeg", 65500},    // libjpeg's JPEG_MAX_DIMENSION (the format itself stops at 65535)
    {"png", 1000000},   // libpng's default user limit (the format itself allows 2^31 - 1)
    {"gif", 65535},     // 16-bit size fields
    {"webp", 16383},    // 14-bit size fields
};

// OIIO keeps sizes in int.
const uint32_t kMaxSide = INT_MAX;

// Attributes of the input that describe its old pixels, layout or file, not the new image.
const char* const kStaleAttributes[] = {
    "oiio:UnassociatedAlpha", "tiff:UnassociatedAlpha", "oiio:BitsPerSample", "Exif:PixelXDimension",
    "Exif:PixelYDimension", "tiff:RowsPerStrip", "tiff:PhotometricInterpretation", "tiff:Compression",
    "tiff:PlanarConfiguration", "planarconfig", "oiio:subimages", "thumbnail_width", "thumbnail_height",
    "thumbnail_nchannels", "thumbnail_image",
};

// Copies the input's metadata. Resolution (dots per inch) scales with the magnification, so a
// print keeps its size; compression settings are per format and copied only to the same one.
void copyMetadata(const Image& like, uint32_t width, uint32_t height, const std::string& format,
                  OIIO::ImageSpec& spec) {
    const OIIO::ImageSpec& from = like.metadata->spec;
    spec.extra_attribs = from.extra_attribs;
    for (const char* stale : kStaleAttributes) spec.erase_attribute(stale);
    if (like.metadata->format_name != format) {
        spec.erase_attribute("compression");
        spec.erase_attribute("CompressionQuality");
    }
    if (like.width && like.height) {
        if (const OIIO::ParamValue* x = from.find_attribute("XResolution", OIIO::TypeDesc::FLOAT))
            spec.attribute("XResolution", x->get_float() * float(width) / float(like.width));
        if (const OIIO::ParamValue* y = from.find_attribute("YResolution", OIIO::TypeDesc::FLOAT))
            spec.attribute("YResolution", y->get_float() * float(height) / float(like.height));
    }
}

// Conventional names, so that OpenEXR readers find grey and alpha again.
std::vector<std::string> channelNames(uint32_t channels) {
    switch (channels) {
        case 1:
            return {"Y"};
        case 2:
            return {"Y", "A"};
        case 3:
            return {"R", "G", "B"};
        default:
            return {"R", "G", "B", "A"};
    }
}

// Copies the finished temporary file to standard output.
void copyToStandardOutput(const std::string& file) {
    auto fail = [](int error) { return UserError(std::string("standard output: ") + std::strerror(error)); };
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw fail(errno);
    const CopyFailure failure =
        copyAll(fd, [](const char* data, size_t size) { return writeAll(STDOUT_FILENO, data, size); });
    ::close(fd);
    if (failure.read_error || failure.write_error) throw fail(failure.write_error ? failure.write_error : failure.read_error);
}

// The extension that names the output format: `format` if given, else the path's.
std::string outputExtension(const std::string& path, const std::string& format) {
    return format.empty() ? fs::path(path).extension().string() : format;
}

}  // namespace

std::string checkOutputFormat(const std::string& path, uint32_t width, uint32_t height, const std::string& format) {
    if (path == kStandardStream && format.empty()) return "the output format must be given (such as png)";
    const std::string extension = outputExtension(path, format);
    const ImageFormat* ours = formatOfExtension(extension);
    if (!ours)
        return (extension.empty() || extension == "." ? std::string("the output has no file extension")
                                                      : "the extension " + extension + " is not a format ddtup writes") +
               " (" + imageFormatTitles() + "; see --format)";
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(ours->oiio_name);
    if (!output) return std::string("OpenImageIO has no ") + ours->title + " writer";
    if (width < 1 || height < 1) return "an image needs at least 1×1 pixels";
    uint32_t max_side = kMaxSide;
    for (const SideLimit& limit : kSideLimits)
        if (output->format_name() == std::string(limit.format)) max_side = limit.max_side;
    if (width > max_side || height > max_side)
        return std::string(output->format_name()) + " holds at most " + std::to_string(max_side) + " pixels a side; the output would be " +
               std::to_string(width) + "×" + std::to_string(height);
    return "";
}

namespace {

// How the premultiplied rows the caller gives become the rows the file stores.
struct OutputLayout {
    uint32_t in_channels = 0;
    uint32_t out_channels = 0;
    bool in_alpha = false;
    bool out_alpha = false;
    bool straight = false;  // divide colour by alpha
    bool flatten = false;   // composite onto white, drop alpha
    bool grey_to_rgb = false;
};

bool needsConversion(const OutputLayout& layout) { return layout.straight || layout.flatten || layout.grey_to_rgb; }

void expandGreyToRgb(OutputLayout& layout) {
    layout.grey_to_rgb = true;
    layout.out_channels += 2;
}

void closeQuietly(OIIO::ImageOutput& output) {
    QuietStderr quiet;  // libpng complains about a file closed without pixels
    output.close();
}

// One pixel from the premultiplied layout the caller gives to the stored layout.
void convertRows(const OutputLayout& layout, const float* in, size_t count, float* out) {
    const uint32_t in_colours = layout.in_channels - (layout.in_alpha ? 1 : 0);
    const uint32_t out_colours = layout.out_channels - (layout.out_alpha ? 1 : 0);
    for (size_t i = 0; i < count; ++i, in += layout.in_channels, out += layout.out_channels) {
        // Colour under zero alpha is lost by premultiplication; it is written as 0.
        const float alpha = layout.in_alpha ? in[layout.in_channels - 1] : 1.0f;
        for (uint32_t k = 0; k < out_colours; ++k) {
            float value = in[k < in_colours ? k : 0];
            if (layout.flatten) value += 1.0f - alpha;
            else if (layout.straight) value = alpha > 0.0f ? value / alpha : 0.0f;
            out[k] = value;
        }
        if (layout.out_alpha) out[out_colours] = alpha;
    }
}

// Whether the file system holding `path` has no space left, to name the cause of a failed
// write by a codec that writes its file itself (TIFF) and reports it in its own words.
bool noSpaceLeft(const std::string& path) {
    struct statvfs status {};
    return ::statvfs(path.c_str(), &status) == 0 && status.f_bavail == 0;
}

// The quality setting of the lossy formats, in OIIO's "compression" attribute.
void setQuality(const std::string& format, int quality, OIIO::ImageSpec& spec) {
    assert(quality >= 1 && quality <= 100);
    if (format == "jpeg" || format == "webp") spec.attribute("compression", format + ":" + std::to_string(quality));
}

}  // namespace

struct ImageWriter::State {
    std::string path;
    std::string name;  // for messages: the path, or "standard output"
    std::unique_ptr<TempFile> temp;
    std::unique_ptr<CheckedFile> file;  // null for the few codecs that cannot write through one
    std::unique_ptr<OIIO::ImageOutput> output;  // OIIO's writer, for every format but PNG
    std::unique_ptr<PngWriter> png;             // ddtup's own, for PNG
    uint32_t width = 0, height = 0;
    OutputLayout layout;
    uint32_t next_row = 0;
    std::vector<float> scratch;

    // The reason a write failed: the file's own error where it saw one, since codecs that
    // ignore failed writes report something vaguer or nothing.
    UserError failure() {
        std::string codec_reason = output ? firstLine(codecError(*output)) : "";  // read either way: it clears it
        if (file && file->failure()) return UserError(name + ": " + std::strerror(file->failure()));
        if (!file && noSpaceLeft(temp->path())) return UserError(name + ": " + std::strerror(ENOSPC));
        return UserError(name + ": cannot write (" + codec_reason + ")");
    }

    // Opens the temporary file as a CheckedFile, empty.
    void openCheckedFile() {
        file.reset();
        try {
            file = std::make_unique<CheckedFile>(temp->path());
        } catch (const std::system_error& error) {
            throw UserError(name + ": cannot write (" + std::strerror(error.code().value()) + ")");
        }
    }

    ~State() {
        if (output) closeQuietly(*output);
    }
};

ImageWriter::ImageWriter(const std::string& path, uint32_t width, uint32_t height, const Image& like,
                         const WriteOptions& options)
    : state_(std::make_unique<State>()) {
    State& s = *state_;
    s.path = path;
    s.name = outputName(path);
    s.width = width;
    s.height = height;
    if (path != kStandardStream) checkOutputPath(path);
    if (std::string problem = checkOutputFormat(path, width, height, options.format); !problem.empty())
        throw UserError(s.name + ": " + problem);
    s.output = OIIO::ImageOutput::create(formatOfExtension(outputExtension(path, options.format))->oiio_name);
    const std::string format = s.output->format_name();
    const SampleType wanted_type = options.depth.value_or(like.sample_type);

    OutputLayout& layout = s.layout;
    layout.in_channels = layout.out_channels = like.channels;
    layout.in_alpha = layout.out_alpha = like.hasAlpha();
    if (like.hasAlpha() && !s.output->supports("alpha")) {
        // Dropping alpha would leave the premultiplied colour, i.e. black under transparent
        // areas; image editors flatten onto white when exporting to such formats, so do we.
        layout.flatten = true;
        layout.out_alpha = false;
        layout.out_channels = like.channels - 1;
        notes_.push_back(s.name + ": " + format + " has no alpha channel; transparent areas are flattened onto white");
    }
    layout.straight = layout.out_alpha && outputAlphaStorage(format, like) == AlphaStorage::Straight;

    s.temp = createTempFile(path);
    // The spec OIIO's writer gets, or for PNG the one ddtup's encoder takes its metadata from.
    auto specFor = [&](OIIO::TypeDesc type) {
        OIIO::ImageSpec spec(int(width), int(height), int(layout.out_channels), type);
        if (like.metadata) copyMetadata(like, width, height, format, spec);
        spec.channelnames = channelNames(layout.out_channels);
        spec.alpha_channel = layout.out_alpha ? int(layout.out_channels) - 1 : -1;
        if (layout.straight) spec.attribute("oiio:UnassociatedAlpha", 1);
        setQuality(format, options.quality, spec);
        return spec;
    };

    if (format == "png") {
        // PNG holds grey and alpha, 8 or 16 bits: wider samples are written as 16 bits.
        const SampleType written = wanted_type == SampleType::UInt8 ? SampleType::UInt8 : SampleType::UInt16;
        s.output.reset();
        s.openCheckedFile();
        State* state = &s;  // owns the writer, so outlives it
        s.png = std::make_unique<PngWriter>(specFor(typeDescOf(written)), [state](const uint8_t* data, size_t size) {
            if (state->file->write(data, size) != size) throw state->failure();
        });
        for (const std::string& missing : s.png->leftOut()) notes_.push_back(s.name + ": " + missing + " is left out");
        if (written != wanted_type)
            notes_.push_back(s.name + ": " + format + " cannot hold " + sampleTypeName(wanted_type) + " samples; written as " +
                             sampleTypeName(written));
        return;
    }

    // OIIO 2.4's TIFF writer loses the main directory when it writes EXIF data through a
    // proxy (measured, with OIIO's own IOFile too); libtiff reports failed writes itself.
    const bool checked = s.output->supports("ioproxy") && format != "tiff";
    auto openAs = [&](OIIO::TypeDesc type) {
        const OIIO::ImageSpec spec = specFor(type);
        if (checked) {
            // Each attempt starts an empty file: a refused one may have written a header.
            s.openCheckedFile();
            s.output->set_ioproxy(s.file.get());
        }
        QuietStderr quiet;
        return s.output->open(s.temp->path(), spec);
    };

    const OIIO::TypeDesc wanted = typeDescOf(wanted_type);
    if (!openAs(wanted)) {
        // Some formats hold no grey (WebP, GIF, HDR) or no grey+alpha (BMP): try RGB(A).
        if (layout.out_channels > 2 || layout.grey_to_rgb) throw s.failure();
        UserError first_failure = s.failure();
        expandGreyToRgb(layout);
        if (!openAs(wanted)) {
            codecError(*s.output);  // drop the second attempt's message, the first says more
            throw first_failure;
        }
    }
    if (layout.grey_to_rgb)
        notes_.push_back(s.name + ": " + format + " cannot hold " + (layout.out_alpha ? "grey+alpha" : "grey") +
                         " images; written as " + (layout.out_alpha ? "RGBA" : "RGB"));
    // Formats that cannot hold a type fall back to 8 bits in OIIO 2.4 (PNG turns float into
    // 8-bit), while 16 bits is nearer for anything wider: ask for it once.
    if (sampleTypeOf(s.output->spec().format) == SampleType::UInt8 && wanted_type != SampleType::UInt8) {
        closeQuietly(*s.output);
        if (!openAs(OIIO::TypeDesc::UINT16)) {
            codecError(*s.output);  // this format refuses 16 bits: back to its own choice
            if (!openAs(wanted)) throw s.failure();
        }
    }
    const SampleType written = sampleTypeOf(s.output->spec().format);
    if (written != wanted_type)
        notes_.push_back(s.name + ": " + format + " cannot hold " + sampleTypeName(wanted_type) +
                         " samples; written as " + sampleTypeName(written));
}

ImageWriter::~ImageWriter() = default;

void ImageWriter::writeRows(uint32_t y_begin, uint32_t y_end, const float* rows) {
    State& s = *state_;
    if (y_begin != s.next_row || y_end > s.height || y_begin >= y_end) throw std::logic_error("rows out of order");
    const float* data = rows;
    if (needsConversion(s.layout)) {
        const size_t count = size_t(y_end - y_begin) * s.width;
        s.scratch.resize(count * s.layout.out_channels);
        parallelFor(count, 1 << 14, [&](size_t begin, size_t end) {
            convertRows(s.layout, rows + begin * s.layout.in_channels, end - begin, s.scratch.data() + begin * s.layout.out_channels);
        });
        data = s.scratch.data();
    }
    if (s.png) {
        s.png->writeRows(data, y_end - y_begin);  // throws at the first failed write
        s.next_row = y_end;
        return;
    }
    bool ok;
    {
        QuietStderr quiet;
        ok = s.output->write_scanlines(int(y_begin), int(y_end), 0, OIIO::TypeDesc::FLOAT, data);
    }
    if (!ok || (s.file && s.file->failure())) throw s.failure();
    s.next_row = y_end;
}

void ImageWriter::commit() {
    State& s = *state_;
    if (s.next_row != s.height) throw std::logic_error("commit before all rows were written");
    bool ok = true;
    if (s.png) {
        s.png->finish();
    } else {
        QuietStderr quiet;
        ok = s.output->close();
    }
    if (s.file) s.file->close();
    if (!ok || (s.file && s.file->failure())) throw s.failure();
    s.output.reset();
    s.png.reset();
    if (s.path == kStandardStream) {
        copyToStandardOutput(s.temp->path());
        return;
    }
    moveIntoPlace(*s.temp, s.path, s.name);
}

std::vector<std::string> writeImage(const std::string& path, const Image& image, const WriteOptions& options) {
    ImageWriter writer(path, image.width, image.height, image, options);
    writer.writeRows(0, image.height, image.pixels.data());
    writer.commit();
    return writer.notes();
}

}  // namespace ddt
