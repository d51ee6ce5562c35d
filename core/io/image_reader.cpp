// Reading image files: checks, standard input, EXIF orientation, straight alpha premultiplied.
// PNG and JPEG files (but CMYK ones) with libpng's and libjpeg's headers and libspng's and
// libjpeg's pixels, without OpenImageIO; the others through OpenImageIO, decoded in bands.
#include "image_file.h"

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <new>
#include <system_error>
#include <type_traits>

#include "checked_file.h"
#include "code_values.h"
#include "image_formats.h"
#include "image_metadata.h"
#include "input_check.h"
#include "jpeg_decoder.h"
#include "oiio_codec.h"
#include "oiio_metadata.h"
#include "png_decoder.h"
#include "png_header.h"
#include "temp_files.h"
#include "upright.h"

namespace ddt {

namespace {

namespace fs = std::filesystem;

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

// Decodes the current image as samples of `type`, its channels interleaved; tiled files as OIIO does.
// The file's own type is asked for as such (UNKNOWN): OIIO 2.4 reads any other request through
// a 64 MiB buffer of its own and converts, even to the same type.
bool decodePixels(OIIO::ImageInput& input, OIIO::TypeDesc type, void* pixels) {
    const OIIO::ImageSpec& spec = input.spec();
    const OIIO::TypeDesc request = spec.channelformats.empty() && type == spec.format ? OIIO::TypeDesc::UNKNOWN : type;
    if (spec.tile_width) return input.read_image(0, 0, 0, spec.nchannels, request, pixels);
    const int band = decodeBandRows(spec);
    const size_t row_bytes = size_t(spec.width) * spec.nchannels * type.size();
    for (int y = 0; y < spec.height; y += band) {
        const int end = std::min(spec.height, y + band);
        if (!input.read_scanlines(0, 0, spec.y + y, spec.y + end, 0, 0, spec.nchannels, request,
                                  static_cast<char*>(pixels) + size_t(y) * row_bytes) ||
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

// What the reader takes from a file's header, whichever library read it.
struct OpenedHeader {
    uint32_t width = 0, height = 0, channels = 0;  // as stored, before any EXIF orientation
    SampleType sample_type = SampleType::UInt8;
    uint32_t code_bits = 0;  // 8 or 16: the samples are kept as such; 0: read as floats
    ImageAttributes attributes;
    std::string format_name;  // OpenImageIO's name of the format ("png", "jpeg", …)
};

void checkPixelCount(const std::string& name, uint64_t width, uint64_t height) {
    if (width * height > kMaxInputPixels)
        throw UserError(name + ": image is " + std::to_string(width) + "×" + std::to_string(height) +
                        " pixels; ddtup reads at most " + std::to_string(kMaxInputPixels) + " pixels (16384×16384)");
}

// A PNG or JPEG file's header without OpenImageIO, its decoder made. nullopt where the file
// needs OpenImageIO: a CMYK or YCCK JPEG, XMP or IPTC metadata, or a header libpng, libspng or
// libjpeg refuses (OpenImageIO's reader then words the reason, as it always has).
std::optional<OpenedHeader> openWithoutOiio(const ImageFormat& format, const std::string& file, const std::string& name,
                                            std::unique_ptr<PngDecoder>& png, std::unique_ptr<JpegDecoder>& jpeg) {
    const DecodeExif decode_exif = decodeExifWithOiio;
    OpenedHeader opened;
    try {
        if (format.oiio_name == std::string("png")) {
            std::optional<PngHeader> header = readPngHeader(file, name, decode_exif);
            if (!header) return std::nullopt;
            png = std::make_unique<PngDecoder>(file, name);
            if (png->width() != header->width || png->height() != header->height || png->channels() != header->channels ||
                png->sampleBits() != header->bits) {
                png.reset();  // OpenImageIO's path reports the disagreement
                return std::nullopt;
            }
            opened = {header->width, header->height, header->channels, header->bits == 16 ? SampleType::UInt16 : SampleType::UInt8,
                      header->bits, std::move(header->attributes), "png"};
        } else if (format.oiio_name == std::string("jpeg")) {
            jpeg = std::make_unique<JpegDecoder>(file, name);
            std::optional<ImageAttributes> attributes;
            if (jpeg->decodable()) attributes = jpeg->attributes(decode_exif);
            if (!attributes) {
                jpeg.reset();
                return std::nullopt;
            }
            opened = {jpeg->width(), jpeg->height(), jpeg->channels(), SampleType::UInt8, 8, std::move(*attributes), "jpeg"};
        } else {
            return std::nullopt;
        }
    } catch (const UserError&) {
        png.reset();
        jpeg.reset();
        return std::nullopt;
    }
    return opened;
}

// Any file through OpenImageIO's reader for its format, its checks made; for PNG and JPEG
// files that openWithoutOiio left, the pixels still come from libspng and libjpeg where they can.
OpenedHeader openWithOiio(const ImageFormat& format, const std::string& file, const std::string& name,
                          std::unique_ptr<OIIO::ImageInput>& input, std::unique_ptr<PngDecoder>& png,
                          std::unique_ptr<JpegDecoder>& jpeg, std::vector<std::string>& notes) {
    // Ask readers for straight alpha as stored; premultiplying in float loses nothing.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    {
        QuietStderr quiet;
        input = OIIO::ImageInput::create(format.oiio_name);
        OIIO::ImageSpec opened;
        if (input && !input->open(file, opened, config)) {
            const std::string reason = firstLine(codecError(*input));
            throw UserError(name + ": not a readable " + format.title + " image (" + reason + ")");
        }
    }
    if (!input) throw std::runtime_error(std::string("OpenImageIO has no ") + format.title + " reader");

    bool several;
    {
        QuietStderr quiet;
        several = hasSeveralImages(*input);
    }
    if (several) notes.push_back(name + ": has more than one image (pages or frames); using the first");
    const OIIO::ImageSpec& spec = input->spec();
    if (spec.deep) throw UserError(name + ": deep images are not supported");
    if (spec.depth > 1) throw UserError(name + ": volume images are not supported");
    if (spec.width < 1 || spec.height < 1) throw UserError(name + ": the image has no pixels");
    checkPixelCount(name, uint64_t(spec.width), uint64_t(spec.height));
    if (std::string problem = checkChannelLayout(spec); !problem.empty()) throw UserError(name + ": " + problem);

    // JPEG and PNG pixels come from libjpeg-turbo (where it takes the colour model) and libspng
    // directly, the same samples (jpeg_decoder.h, png_decoder.h).
    auto check_layout = [&](uint32_t width, uint32_t height, uint32_t channels, uint32_t bits) {
        if (width != uint32_t(spec.width) || height != uint32_t(spec.height) || channels != uint32_t(spec.nchannels) ||
            bits != spec.format.size() * 8)
            throw std::logic_error(name + ": the decoder and OpenImageIO disagree on the image's layout");
    };
    if (format.oiio_name == std::string("jpeg")) {
        jpeg = std::make_unique<JpegDecoder>(file, name);
        if (!jpeg->decodable()) jpeg.reset();
        else check_layout(jpeg->width(), jpeg->height(), jpeg->channels(), 8);
    }
    if (format.oiio_name == std::string("png")) {
        png = std::make_unique<PngDecoder>(file, name);
        check_layout(png->width(), png->height(), png->channels(), png->sampleBits());
    }
    OpenedHeader opened{uint32_t(spec.width), uint32_t(spec.height), uint32_t(spec.nchannels), sampleTypeOf(spec.format), 0,
                        attributesOf(spec), input->format_name()};
    // Signed and mixed per-channel types are converted to floats as they are read.
    if (spec.channelformats.empty() && (spec.format == OIIO::TypeDesc::UINT8 || spec.format == OIIO::TypeDesc::UINT16))
        opened.code_bits = uint32_t(spec.format.size() * 8);
    return opened;
}

}  // namespace

struct ImageReader::State {
    std::string name;                      // for messages: the path, or "standard input"
    std::unique_ptr<TempFile> stdin_copy;  // what is read when the path is "-"
    std::string file;                      // the path, or the copy of standard input
    std::unique_ptr<JpegDecoder> jpeg;     // decodes the pixels of a grey, YCbCr or RGB JPEG file
    std::unique_ptr<PngDecoder> png;       // decodes the pixels of a PNG file
    std::unique_ptr<OIIO::ImageInput> input;  // decodes the others; null where the two above do
    AlphaStorage alpha_storage = AlphaStorage::Premultiplied;
    int orientation = 1;
    uint32_t stored_width = 0, stored_height = 0;  // before the orientation is applied
    uint32_t code_bits = 0;                        // 8 or 16: the samples are kept as such; 0: as floats
    bool decoded = false;
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
    s.file = file;

    // Only the reader of the file's own format, one of ours, sees it: OIIO's open() would try
    // every reader it has (image_formats.h). The content decides, so a mis-named file or the
    // extension-less copy of standard input is recognised.
    const ImageFormat* format = formatOfContent(file, s.stdin_copy ? std::string() : path);
    if (!format)
        throw UserError(s.name + ": not an image in a format ddtup reads (" + imageFormatTitles() + ")");
    if (std::string problem = checkBeforeDecoding(file, format->oiio_name); !problem.empty())
        throw UserError(s.name + ": " + problem);

    std::optional<OpenedHeader> opened = openWithoutOiio(*format, file, s.name, s.png, s.jpeg);
    if (opened) checkPixelCount(s.name, opened->width, opened->height);
    else opened = openWithOiio(*format, file, s.name, s.input, s.png, s.jpeg, notes_);

    s.orientation = 1;
    const int orientation = opened->attributes.getInt("Orientation", 1);
    if (orientation >= 2 && orientation <= 8) s.orientation = orientation;
    const bool swapped = swapsSides(s.orientation);
    s.stored_width = opened->width;
    s.stored_height = opened->height;
    s.code_bits = opened->code_bits;

    auto metadata = std::make_shared<ImageMetadata>();
    metadata->attributes = std::move(opened->attributes);
    metadata->format_name = opened->format_name;
    metadata->alpha_storage = inputAlphaStorage(metadata->attributes, metadata->format_name);
    // The metadata describes the upright image the reader returns.
    ImageAttributes& attributes = metadata->attributes;
    attributes.erase("Orientation");
    if (swapped) {
        const float x_resolution = attributes.getFloat("XResolution", 0.0f);
        const float y_resolution = attributes.getFloat("YResolution", 0.0f);
        if (x_resolution > 0.0f && y_resolution > 0.0f) {
            attributes.set("XResolution", y_resolution);
            attributes.set("YResolution", x_resolution);
        }
    }
    s.alpha_storage = metadata->alpha_storage;

    header_.width = swapped ? opened->height : opened->width;
    header_.height = swapped ? opened->width : opened->height;
    header_.channels = opened->channels;
    header_.sample_type = opened->sample_type;
    header_.metadata = metadata;
}


ImageReader::~ImageReader() = default;

template <class Sample>
std::vector<Sample> ImageReader::decode() {
    State& s = *state_;
    if (s.decoded) throw std::logic_error("ImageReader::read called twice");
    s.decoded = true;
    std::vector<Sample> samples;
    try {
        samples.resize(size_t(header_.width) * header_.height * header_.channels);
    } catch (const std::bad_alloc&) {
        throw UserError(s.name + ": too large to hold in memory (" + std::to_string(header_.width) + "×" +
                        std::to_string(header_.height) + ")");
    }
    bool decoded = false;
    if constexpr (std::is_same_v<Sample, uint8_t>) {
        if (s.jpeg) {
            s.jpeg->decode(samples.data());
            decoded = true;
        }
    }
    if constexpr (std::is_same_v<Sample, uint8_t> || std::is_same_v<Sample, uint16_t>) {
        if (s.png) {  // its depth is the file's (checked against the header's), which chose Sample
            s.png->decode(samples.data());
            decoded = true;
        }
    }
    if (!decoded) {
        if (!s.input) throw std::logic_error(s.name + ": no decoder for these samples");
        const OIIO::TypeDesc type = OIIO::BaseTypeFromC<Sample>::value;
        bool ok;
        {
            QuietStderr quiet;
            ok = decodePixels(*s.input, type, samples.data());
        }
        // libjpeg fills a truncated file with grey and OIIO returns success, but records the error.
        if (!ok || s.input->has_error())
            throw UserError(s.name + ": truncated or corrupt image (" + firstLine(codecError(*s.input)) + ")");
    }
    s.jpeg.reset();
    s.png.reset();
    s.input.reset();
    s.stdin_copy.reset();
    makeUpright(samples.data(), sizeof(Sample) * header_.channels, s.stored_width, s.stored_height, s.orientation);
    return samples;
}

PackedImage ImageReader::readPacked() {
    const bool straight = header_.hasAlpha() && state_->alpha_storage == AlphaStorage::Straight;
    // 8- and 16-bit files are kept as their codes (packed_image.h); anything else as floats.
    if (state_->code_bits == 8) {
        std::vector<uint8_t> codes = decode<uint8_t>();
        return PackedImage(header_, std::move(codes), valuesOfCodes(8), straight);
    }
    if (state_->code_bits == 16) {
        std::vector<uint16_t> codes = decode<uint16_t>();
        return PackedImage(header_, std::move(codes), valuesOfCodes(16), straight);
    }
    Image image = header_;
    image.pixels = decode<float>();
    // Interpolating across a NaN or an infinity spreads it over the whole neighbourhood.
    if ((image.sample_type == SampleType::Half || image.sample_type == SampleType::Float) && !allFinite(image.pixels))
        throw UserError(state_->name + ": contains NaN or infinite values");
    if (straight) premultiply(image.pixels.data(), image.pixels.size(), image.channels);
    return PackedImage(std::move(image));
}

Image ImageReader::read() { return readPacked().unpack(); }

uint32_t ImageReader::keptSampleBytes() const {
    return state_->code_bits ? state_->code_bits / 8 : uint32_t(sizeof(float));
}

Image readImage(const std::string& path) { return ImageReader(path).read(); }

}  // namespace ddt
