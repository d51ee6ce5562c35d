// Writing image files: format limits checked first, a temporary file renamed over the output
// on commit, PNG and JPEG through ddtup's own encoders, every other format through
// OpenImageIO's codecs (codec_module.h).
#include "image_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cassert>
#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>

#include "checked_file.h"
#include "codec_module.h"
#include "exif.h"
#include "image_formats.h"
#include "image_metadata.h"
#include "iptc.h"
#include "jpeg_encoder.h"
#include "output_file.h"
#include "output_layout.h"
#include "parallel.h"
#include "png_writer.h"
#include "temp_files.h"
#include "xmp.h"

namespace ddt {

namespace {

namespace fs = std::filesystem;

// The largest side a format can hold, checked before any work: libjpeg (under ddtup's JPEG
// writer) ends the whole process past its limit, libpng's readers refuse PNG files past theirs,
// and OpenImageIO 2.4's GIF writer makes corrupt files, its WebP writer fails only after all
// the work (measured).
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
    if (width < 1 || height < 1) return "an image needs at least 1×1 pixels";
    uint32_t max_side = kMaxSide;
    for (const SideLimit& limit : kSideLimits)
        if (ours->oiio_name == std::string(limit.format)) max_side = limit.max_side;
    if (width > max_side || height > max_side)
        return std::string(ours->oiio_name) + " holds at most " + std::to_string(max_side) + " pixels a side; the output would be " +
               std::to_string(width) + "×" + std::to_string(height);
    return "";
}

namespace {

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

// The quality setting of the lossy formats, in OIIO's "compression" attribute.
void setQuality(const std::string& format, int quality, ImageAttributes& attributes) {
    assert(quality >= 1 && quality <= 100);
    if (format == "jpeg" || format == "webp") attributes.set("compression", format + ":" + std::to_string(quality));
}

}  // namespace

struct ImageWriter::State {
    std::string path;
    std::string name;  // for messages: the path, or "standard output"
    std::unique_ptr<TempFile> temp;
    std::unique_ptr<CheckedFile> file;    // what ddtup's own encoder writes to
    std::unique_ptr<PngWriter> png;       // ddtup's own, for PNG
    std::unique_ptr<JpegWriter> jpeg;     // ddtup's own, for JPEG
    std::unique_ptr<CodecOutput> output;  // OpenImageIO's writer, for every other format
    uint32_t width = 0, height = 0;
    OutputLayout layout;
    uint32_t next_row = 0;
    std::vector<float> scratch;

    // ImageWriter::writeCodes.
    template <typename Sample>
    void writeCodes(uint32_t y_begin, uint32_t y_end, const Sample* codes);

    // The reason a write to `file` failed.
    UserError failure() const { return UserError(name + ": " + std::strerror(file->failure())); }

    // Opens the temporary file for ddtup's own encoders.
    void openFile() {
        try {
            file = std::make_unique<CheckedFile>(temp->path());
        } catch (const std::system_error& error) {
            throw UserError(name + ": cannot write (" + std::strerror(error.code().value()) + ")");
        }
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
    const ImageFormat& image_format = *formatOfExtension(outputExtension(path, options.format));
    const std::string format = image_format.oiio_name;
    const SampleType wanted_type = options.depth.value_or(like.sample_type);

    OutputLayout& layout = s.layout;
    layout.in_channels = layout.out_channels = like.channels;
    layout.in_alpha = layout.out_alpha = like.hasAlpha();
    const bool writes_alpha = format == "png" || (format != "jpeg" && codecModule().writesAlpha(image_format));
    if (like.hasAlpha() && !writes_alpha) {
        // Dropping alpha would leave the premultiplied colour, i.e. black under transparent
        // areas; image editors flatten onto white when exporting to such formats, so do we.
        layout.flatten = true;
        layout.out_alpha = false;
        layout.out_channels = like.channels - 1;
        notes_.push_back(s.name + ": " + format + " has no alpha channel; transparent areas are flattened onto white");
    }
    layout.straight = layout.out_alpha && outputAlphaStorage(format, like) == AlphaStorage::Straight;

    s.temp = createTempFile(path);
    // The attributes the file gets.
    auto attributesFor = [&]() {
        ImageAttributes attributes;
        if (like.metadata) attributes = outputAttributes(like, width, height, format);
        if (layout.straight) attributes.set("oiio:UnassociatedAlpha", 1);
        setQuality(format, options.quality, attributes);
        return attributes;
    };
    if (format == "png") {
        // PNG holds grey and alpha, 8 or 16 bits: wider samples are written as 16 bits.
        const SampleType written = wanted_type == SampleType::UInt8 ? SampleType::UInt8 : SampleType::UInt16;
        s.openFile();
        State* state = &s;  // owns the writer, so outlives it
        const PngFormat png_format{width, height, layout.out_channels, written == SampleType::UInt8 ? 8u : 16u};
        PngMetadataSource metadata;
        metadata.attributes = attributesFor();
        metadata.channels = layout.out_channels;
        metadata.exif = encodeExif(metadata.attributes);
        s.png = std::make_unique<PngWriter>(png_format, metadata, [state](const uint8_t* data, size_t size) {
            if (state->file->write(data, size) != size) throw state->failure();
        });
        for (const std::string& missing : s.png->leftOut()) notes_.push_back(s.name + ": " + missing + " is left out");
        if (written != wanted_type)
            notes_.push_back(s.name + ": " + format + " cannot hold " + sampleTypeName(wanted_type) + " samples; written as " +
                             sampleTypeName(written));
        return;
    }

    if (format == "jpeg") {
        s.openFile();
        State* state = &s;  // owns the writer, so outlives it
        JpegMetadata metadata;
        metadata.attributes = jpegAttributes(attributesFor());
        metadata.exif = encodeExifBlock(metadata.attributes);
        metadata.iptc = encodeIptc(metadata.attributes);
        metadata.xmp = encodeXmp(metadata.attributes);
        const JpegFormat jpeg_format{width, height, layout.out_channels, options.quality};
        s.jpeg = std::make_unique<JpegWriter>(jpeg_format, metadata, [state](const uint8_t* data, size_t size) {
            if (state->file->write(data, size) != size) throw state->failure();
        });
        for (const std::string& missing : s.jpeg->leftOut()) notes_.push_back(s.name + ": " + missing + " is left out");
        if (wanted_type != SampleType::UInt8)
            notes_.push_back(s.name + ": " + format + " cannot hold " + sampleTypeName(wanted_type) + " samples; written as " +
                             sampleTypeName(SampleType::UInt8));
        return;
    }

    OutputRequest request;
    request.temp_path = s.temp->path();
    request.name = s.name;
    request.format = &image_format;
    request.width = width;
    request.height = height;
    request.wanted = wanted_type;
    request.attributes = attributesFor();
    s.output = codecModule().openOutput(request, layout);
    if (layout.grey_to_rgb)
        notes_.push_back(s.name + ": " + format + " cannot hold " + (layout.out_alpha ? "grey+alpha" : "grey") +
                         " images; written as " + (layout.out_alpha ? "RGBA" : "RGB"));
    const SampleType written = s.output->written();
    if (written != wanted_type)
        notes_.push_back(s.name + ": " + format + " cannot hold " + sampleTypeName(wanted_type) +
                         " samples; written as " + sampleTypeName(written));
}

ImageWriter::~ImageWriter() = default;

template <typename Sample>
void ImageWriter::State::writeCodes(uint32_t y_begin, uint32_t y_end, const Sample* codes) {
    if (y_begin != next_row || y_end > height || y_begin >= y_end) throw std::logic_error("rows out of order");
    if (needsConversion(layout) || !(png || (jpeg && sizeof(Sample) == 1)))
        throw std::logic_error("the writer does not take these codes");
    if (png) {
        png->writeCodes(codes, y_end - y_begin);  // throws at the first failed write
    } else if constexpr (sizeof(Sample) == 1) {
        jpeg->writeCodes(codes, y_end - y_begin);
    }
    next_row = y_end;
}

void ImageWriter::writeCodes(uint32_t y_begin, uint32_t y_end, const uint8_t* codes) {
    state_->writeCodes(y_begin, y_end, codes);
}
void ImageWriter::writeCodes(uint32_t y_begin, uint32_t y_end, const uint16_t* codes) {
    state_->writeCodes(y_begin, y_end, codes);
}

uint32_t ImageWriter::codeBits() const {
    const State& s = *state_;
    if (needsConversion(s.layout)) return 0;
    if (s.png) return s.png->bitDepth();
    return s.jpeg ? 8 : 0;
}

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
    if (s.jpeg) {
        s.jpeg->writeRows(data, y_end - y_begin);  // throws at the first failed write
        s.next_row = y_end;
        return;
    }
    s.output->writeRows(y_begin, y_end, data);
    s.next_row = y_end;
}

void ImageWriter::commit() {
    State& s = *state_;
    if (s.next_row != s.height) throw std::logic_error("commit before all rows were written");
    if (s.png || s.jpeg) {
        if (s.png) s.png->finish();
        if (s.jpeg) s.jpeg->finish();
        s.file->close();
        if (s.file->failure()) throw s.failure();
    } else {
        s.output->finish();
    }
    s.output.reset();
    s.png.reset();
    s.jpeg.reset();
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
