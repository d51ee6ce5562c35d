#include "image.h"

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <new>
#include <set>

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
// points at /dev/null for the duration of each call into a codec, and only then.
class QuietStderr {
public:
    QuietStderr() {
        std::fflush(stderr);
        int null_fd = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
        if (null_fd < 0) return;
        saved_fd_ = ::fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 0);
        if (saved_fd_ >= 0) ::dup2(null_fd, STDERR_FILENO);
        ::close(null_fd);
    }
    ~QuietStderr() {
        if (saved_fd_ < 0) return;
        std::fflush(stderr);
        ::dup2(saved_fd_, STDERR_FILENO);
        ::close(saved_fd_);
    }
    QuietStderr(const QuietStderr&) = delete;
    QuietStderr& operator=(const QuietStderr&) = delete;

private:
    int saved_fd_ = -1;
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
// Asked with "oiio:UnassociatedAlpha", the PNG, Targa, TIFF (unassociated) and HEIF readers
// return straight colour and say so in that attribute. BMP and ICO readers return their
// straight colour as stored without saying so. OpenEXR and associated TIFF come back as
// stored, premultiplied, which is also OIIO's convention for every other reader.
AlphaStorage inputAlphaStorage(const OIIO::ImageSpec& spec, const std::string& format) {
    if (spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0) return AlphaStorage::Straight;
    if (format == "bmp" || format == "ico") return AlphaStorage::Straight;
    return AlphaStorage::Premultiplied;
}

// Formats whose files hold straight colour: the PNG, Targa, WebP, HEIF and JPEG 2000 writers
// store straight colour given with "oiio:UnassociatedAlpha" as is (without it they divide by
// alpha after rounding to the file's depth, which loses precision); BMP and ICO writers store
// whatever they get. TIFF can hold either and keeps the input's choice, so -s 1 reproduces
// it. Every other format gets premultiplied colour: OpenEXR requires it, and it is OIIO's
// convention for formats that do not say.
AlphaStorage outputAlphaStorage(const std::string& format, const Image& like) {
    static const std::set<std::string> straight = {"png", "targa", "webp", "heif", "jpeg2000", "bmp", "ico"};
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

const char* sampleTypeName(SampleType type) {
    switch (type) {
        case SampleType::UInt8:
            return "8-bit";
        case SampleType::UInt16:
            return "16-bit";
        case SampleType::Half:
            return "half float";
        case SampleType::Float:
            break;
    }
    return "float";
}

struct ImageReader::State {
    std::string path;
    std::unique_ptr<OIIO::ImageInput> input;
    AlphaStorage alpha_storage = AlphaStorage::Premultiplied;
};

ImageReader::ImageReader(const std::string& path) : state_(std::make_unique<State>()) {
    State& s = *state_;
    s.path = path;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) throw UserError(path + ": no such file");
    if (fs::is_directory(status)) throw UserError(path + ": is a folder, not an image");
    // Devices and pipes can feed a reader forever (/dev/zero) or block it.
    if (!fs::is_regular_file(status)) throw UserError(path + ": not a regular file");
    if (::access(path.c_str(), R_OK) != 0) throw UserError(path + ": cannot open (" + std::strerror(errno) + ")");

    // Ask readers for straight alpha as stored; premultiplying in float loses nothing.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    {
        QuietStderr quiet;
        s.input = OIIO::ImageInput::open(path, &config);
    }
    if (!s.input) throw UserError(path + ": not a readable image (" + firstLine(globalError()) + ")");

    const OIIO::ImageSpec& spec = s.input->spec();
    if (spec.deep) throw UserError(path + ": deep images are not supported");
    if (spec.depth > 1) throw UserError(path + ": volume images are not supported");
    if (spec.width < 1 || spec.height < 1) throw UserError(path + ": the image has no pixels");
    if (std::string problem = checkChannelLayout(spec); !problem.empty()) throw UserError(path + ": " + problem);

    auto metadata = std::make_shared<ImageMetadata>();
    metadata->spec = spec;
    metadata->format_name = s.input->format_name();
    metadata->alpha_storage = inputAlphaStorage(spec, metadata->format_name);
    s.alpha_storage = metadata->alpha_storage;

    header_.width = uint32_t(spec.width);
    header_.height = uint32_t(spec.height);
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
        throw UserError(s.path + ": too large to hold in memory (" + std::to_string(image.width) + "×" +
                        std::to_string(image.height) + ")");
    }
    bool ok;
    {
        QuietStderr quiet;
        ok = s.input->read_image(0, 0, 0, int(image.channels), OIIO::TypeDesc::FLOAT, image.pixels.data());
    }
    // libjpeg fills a truncated file with grey and OIIO returns success, but records the error.
    if (!ok || s.input->has_error())
        throw UserError(s.path + ": truncated or corrupt image (" + firstLine(codecError(*s.input)) + ")");
    s.input.reset();
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

// Creates the hidden sibling of `path` that the image is written to, so the final rename stays
// within one file system. Throws with the system's reason when the folder is not writable.
std::string createTempFile(const std::string& path) {
    const fs::path target(path);
    const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    const std::string prefix = target.filename().string().insert(0, 1, '.') + ".ddtup-" + std::to_string(::getpid());
    for (int attempt = 0;; ++attempt) {
        const fs::path temp = folder / (prefix + "-" + std::to_string(attempt));
        int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            ::close(fd);
            return temp.string();
        }
        if (errno != EEXIST || attempt == 99)
            throw UserError(path + ": cannot write in folder " + folder.string() + " (" + std::strerror(errno) + ")");
    }
}

// Refuses outputs that are not a plain replaceable file in an existing folder.
void checkOutputPath(const std::string& path) {
    std::error_code ec;
    const fs::path target(path);
    const fs::file_status status = fs::status(target, ec);  // through symlinks
    if (fs::is_directory(status)) throw UserError(path + ": is a folder");
    if (fs::exists(status) && !fs::is_regular_file(status))
        throw UserError(path + ": not a regular file; refusing to replace it");
    if (fs::exists(status) && ::access(path.c_str(), W_OK) != 0)
        throw UserError(path + ": the file is read-only; refusing to replace it");
    const fs::path folder = target.parent_path();
    if (folder.empty() || fs::is_directory(folder, ec)) return;
    if (fs::exists(folder, ec)) throw UserError(path + ": " + folder.string() + " is not a folder");
    throw UserError(path + ": folder " + folder.string() + " does not exist");
}

}  // namespace

std::string checkOutputFormat(const std::string& path, uint32_t width, uint32_t height) {
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(path);
    if (!output) {
        globalError();  // clear it: the message names no reason the user can act on
        return "no image format is known for this file extension";
    }
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

}  // namespace

struct ImageWriter::State {
    std::string path;
    std::string temp_path;
    std::unique_ptr<OIIO::ImageOutput> output;
    uint32_t width = 0, height = 0;
    OutputLayout layout;
    uint32_t next_row = 0;
    bool committed = false;
    std::vector<float> scratch;

    ~State() {
        if (committed) return;
        if (output) closeQuietly(*output);
        std::error_code ec;
        if (!temp_path.empty()) fs::remove(temp_path, ec);
    }
};

ImageWriter::ImageWriter(const std::string& path, uint32_t width, uint32_t height, const Image& like)
    : state_(std::make_unique<State>()) {
    State& s = *state_;
    s.path = path;
    s.width = width;
    s.height = height;
    checkOutputPath(path);
    if (std::string problem = checkOutputFormat(path, width, height); !problem.empty())
        throw UserError(path + ": " + problem);
    s.output = OIIO::ImageOutput::create(path);
    const std::string format = s.output->format_name();

    OutputLayout& layout = s.layout;
    layout.in_channels = layout.out_channels = like.channels;
    layout.in_alpha = layout.out_alpha = like.hasAlpha();
    if (like.hasAlpha() && !s.output->supports("alpha")) {
        // Dropping alpha would leave the premultiplied colour, i.e. black under transparent
        // areas; image editors flatten onto white when exporting to such formats, so do we.
        layout.flatten = true;
        layout.out_alpha = false;
        layout.out_channels = like.channels - 1;
        notes_.push_back(path + ": " + format + " has no alpha channel; transparent areas are flattened onto white");
    }
    layout.straight = layout.out_alpha && outputAlphaStorage(format, like) == AlphaStorage::Straight;
    // OIIO 2.4's DPX writer aborts the process on grey+alpha.
    if (format == "dpx" && layout.out_channels == 2) expandGreyToRgb(layout);

    auto openAs = [&](OIIO::TypeDesc type) {
        OIIO::ImageSpec spec(int(width), int(height), int(layout.out_channels), type);
        if (like.metadata) copyMetadata(like, width, height, format, spec);
        spec.channelnames = channelNames(layout.out_channels);
        spec.alpha_channel = layout.out_alpha ? int(layout.out_channels) - 1 : -1;
        if (layout.straight) spec.attribute("oiio:UnassociatedAlpha", 1);
        QuietStderr quiet;
        return s.output->open(s.temp_path, spec);
    };
    auto failure = [&] { return UserError(path + ": cannot write (" + firstLine(codecError(*s.output)) + ")"); };

    s.temp_path = createTempFile(path);
    const OIIO::TypeDesc wanted = typeDescOf(like.sample_type);
    if (!openAs(wanted)) {
        // Some formats hold no grey (WebP, GIF, IFF, HDR) or no grey+alpha (BMP): try RGB(A).
        if (layout.out_channels > 2 || layout.grey_to_rgb) throw failure();
        UserError first_failure = failure();
        expandGreyToRgb(layout);
        if (!openAs(wanted)) {
            codecError(*s.output);  // drop the second attempt's message, the first says more
            throw first_failure;
        }
    }
    if (layout.grey_to_rgb)
        notes_.push_back(path + ": " + format + " cannot hold " + (layout.out_alpha ? "grey+alpha" : "grey") +
                         " images; written as " + (layout.out_alpha ? "RGBA" : "RGB"));
    // Formats that cannot hold a type fall back to 8 bits in OIIO 2.4 (PNG turns float into
    // 8-bit), while 16 bits is nearer for anything wider: ask for it once.
    if (sampleTypeOf(s.output->spec().format) == SampleType::UInt8 && like.sample_type != SampleType::UInt8) {
        closeQuietly(*s.output);
        if (!openAs(OIIO::TypeDesc::UINT16)) {
            codecError(*s.output);  // this format refuses 16 bits: back to its own choice
            if (!openAs(wanted)) throw failure();
        }
    }
    const SampleType written = sampleTypeOf(s.output->spec().format);
    if (written != like.sample_type)
        notes_.push_back(path + ": " + format + " cannot hold " + sampleTypeName(like.sample_type) +
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
        convertRows(s.layout, rows, count, s.scratch.data());
        data = s.scratch.data();
    }
    bool ok;
    {
        QuietStderr quiet;
        ok = s.output->write_scanlines(int(y_begin), int(y_end), 0, OIIO::TypeDesc::FLOAT, data);
    }
    if (!ok) throw UserError(s.path + ": cannot write (" + firstLine(codecError(*s.output)) + ")");
    s.next_row = y_end;
}

void ImageWriter::commit() {
    State& s = *state_;
    if (s.next_row != s.height) throw std::logic_error("commit before all rows were written");
    bool ok;
    {
        QuietStderr quiet;
        ok = s.output->close();
    }
    if (!ok) throw UserError(s.path + ": cannot write (" + firstLine(codecError(*s.output)) + ")");
    s.output.reset();
    std::error_code ec;
    fs::rename(s.temp_path, s.path, ec);
    if (ec) throw UserError(s.path + ": cannot replace the file (" + ec.message() + ")");
    s.committed = true;
}

std::vector<std::string> writeImage(const std::string& path, const Image& image) {
    ImageWriter writer(path, image.width, image.height, image);
    writer.writeRows(0, image.height, image.pixels.data());
    writer.commit();
    return writer.notes();
}

}  // namespace ddt
