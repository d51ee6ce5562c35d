// Reading image files: checks, standard input, EXIF orientation, straight alpha premultiplied.
// PNG and JPEG files read by ddtup itself (headers by libpng and libjpeg, pixels by libspng and
// libjpeg-turbo); everything else, CMYK JPEGs and files with XMP or IPTC by OpenImageIO's
// codecs (codec_module.h), whose module is then loaded.
#include "image_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <new>
#include <optional>
#include <system_error>
#include <type_traits>

#include "checked_file.h"
#include "code_values.h"
#include "codec_module.h"
#include "exif.h"
#include "image_formats.h"
#include "image_metadata.h"
#include "input_check.h"
#include "jpeg_decoder.h"
#include "png_decoder.h"
#include "png_header.h"
#include "temp_files.h"
#include "upright.h"
#include "user_error.h"

namespace ddt {

namespace {

namespace fs = std::filesystem;

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

uint32_t bitsOf(SampleType type) { return type == SampleType::UInt8 ? 8 : type == SampleType::Float ? 32 : 16; }

template <class Sample>
SampleType sampleTypeOfC() {
    if constexpr (std::is_same_v<Sample, uint8_t>) return SampleType::UInt8;
    else if constexpr (std::is_same_v<Sample, uint16_t>) return SampleType::UInt16;
    else return SampleType::Float;
}

// EXIF blocks by ddtup's own decoder (exif.h), which follows OpenImageIO's rules.
void decodeExifBlock(const uint8_t* block, size_t size, ImageAttributes& attributes) { decodeExif(block, size, attributes); }

// A PNG or JPEG file's header without OpenImageIO, its decoder made. nullopt where the file
// needs OpenImageIO: a CMYK or YCCK JPEG, XMP or IPTC metadata, or a header libpng, libspng or
// libjpeg refuses (OpenImageIO's reader then words the reason, as it always has).
std::optional<StoredImage> openWithoutOiio(const ImageFormat& format, const std::string& file, const std::string& name,
                                           std::unique_ptr<PngDecoder>& png, std::unique_ptr<JpegDecoder>& jpeg) {
    StoredImage stored;
    try {
        if (format.oiio_name == std::string("png")) {
            std::optional<PngHeader> header = readPngHeader(file, name, decodeExifBlock);
            if (!header) return std::nullopt;
            png = std::make_unique<PngDecoder>(file, name);
            if (png->width() != header->width || png->height() != header->height || png->channels() != header->channels ||
                png->sampleBits() != header->bits) {
                png.reset();  // OpenImageIO's path reports the disagreement
                return std::nullopt;
            }
            stored.width = header->width;
            stored.height = header->height;
            stored.channels = header->channels;
            stored.sample_type = header->bits == 16 ? SampleType::UInt16 : SampleType::UInt8;
            stored.attributes = std::move(header->attributes);
        } else if (format.oiio_name == std::string("jpeg")) {
            jpeg = std::make_unique<JpegDecoder>(file, name);
            std::optional<ImageAttributes> attributes;
            if (jpeg->decodable()) attributes = jpeg->attributes(decodeExifBlock);
            if (!attributes) {
                jpeg.reset();
                return std::nullopt;
            }
            stored.width = jpeg->width();
            stored.height = jpeg->height();
            stored.channels = jpeg->channels();
            stored.attributes = std::move(*attributes);
        } else {
            return std::nullopt;
        }
    } catch (const UserError&) {
        png.reset();
        jpeg.reset();
        return std::nullopt;
    }
    stored.keeps_codes = true;
    stored.format_name = format.oiio_name;
    return stored;
}

// A JPEG's or PNG's rows for a PackedImage that takes them as its tiles need them. It keeps
// the decoder, and the copy of standard input that the decoder reads.
class FileRows : public RowDecoder {
public:
    FileRows(std::unique_ptr<JpegDecoder> jpeg, std::unique_ptr<PngDecoder> png, std::unique_ptr<TempFile> stdin_copy)
        : jpeg_(std::move(jpeg)), png_(std::move(png)), stdin_copy_(std::move(stdin_copy)) {}

    void decodeRows(uint32_t count, void* codes) override {
        try {
            if (jpeg_) jpeg_->decodeRows(count, static_cast<uint8_t*>(codes));
            else png_->decodeRows(count, codes);
        } catch (const UserError& error) {
            throw InputError(error.what());  // it names the file
        }
    }

private:
    std::unique_ptr<JpegDecoder> jpeg_;
    std::unique_ptr<PngDecoder> png_;
    std::unique_ptr<TempFile> stdin_copy_;
};

bool allFinite(const std::vector<float>& pixels) {
    for (float value : pixels)
        if (!std::isfinite(value)) return false;
    return true;
}

}  // namespace

struct ImageReader::State {
    std::string name;                      // for messages: the path, or "standard input"
    std::unique_ptr<TempFile> stdin_copy;  // what is read when the path is "-"
    std::string file;                      // the path, or the copy of standard input
    std::unique_ptr<JpegDecoder> jpeg;     // decodes the pixels of a grey, YCbCr or RGB JPEG file
    std::unique_ptr<PngDecoder> png;       // decodes the pixels of a PNG file
    std::unique_ptr<CodecInput> input;     // the header, and the pixels of every other file
    StoredImage stored;                    // the header as stored, before the EXIF orientation
    AlphaStorage alpha_storage = AlphaStorage::Premultiplied;
    int orientation = 1;
    std::optional<SampleType> codes;  // UInt8 or UInt16: the samples are kept as such
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
    std::optional<StoredImage> own = openWithoutOiio(*format, file, s.name, s.png, s.jpeg);
    if (own) {
        s.stored = std::move(*own);
    } else {
        s.input = codecModule().openInput(file, s.name, *format);
        s.stored = s.input->stored();
    }
    const StoredImage& stored = s.stored;
    if (stored.several_images) notes_.push_back(s.name + ": has more than one image (pages or frames); using the first");
    if (uint64_t(stored.width) * uint64_t(stored.height) > kMaxInputPixels)
        throw UserError(s.name + ": image is " + std::to_string(stored.width) + "×" + std::to_string(stored.height) +
                        " pixels; ddtup reads at most " + std::to_string(kMaxInputPixels) + " pixels (16384×16384)");
    if (!stored.channel_layout_problem.empty()) throw UserError(s.name + ": " + stored.channel_layout_problem);

    const int orientation = stored.attributes.getInt("Orientation", 1);
    if (orientation >= 2 && orientation <= 8) s.orientation = orientation;
    const bool swapped = swapsSides(s.orientation);

    auto metadata = std::make_shared<ImageMetadata>();
    metadata->attributes = stored.attributes;
    metadata->format_name = stored.format_name;
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

    header_.width = swapped ? stored.height : stored.width;
    header_.height = swapped ? stored.width : stored.height;
    header_.channels = stored.channels;
    header_.sample_type = stored.sample_type;
    header_.metadata = metadata;
    // Where OpenImageIO read the header, JPEG and PNG pixels still come from libjpeg-turbo
    // (where it takes the colour model) and libspng, the same samples (jpeg_decoder.h,
    // png_decoder.h); openWithoutOiio made the decoders for the files it read.
    auto check_layout = [&](uint32_t width, uint32_t height, uint32_t channels, uint32_t bits) {
        if (width != stored.width || height != stored.height || channels != stored.channels ||
            bits != bitsOf(stored.sample_type))
            throw std::logic_error(s.name + ": the decoder and OpenImageIO disagree on the image's layout");
    };
    if (s.input && format->oiio_name == std::string("jpeg")) {
        s.jpeg = std::make_unique<JpegDecoder>(s.file, s.name);
        if (!s.jpeg->decodable()) s.jpeg.reset();
        else check_layout(s.jpeg->width(), s.jpeg->height(), s.jpeg->channels(), 8);
    } else if (s.input && format->oiio_name == std::string("png")) {
        s.png = std::make_unique<PngDecoder>(s.file, s.name);
        check_layout(s.png->width(), s.png->height(), s.png->channels(), s.png->sampleBits());
    }
    if (stored.keeps_codes) s.codes = stored.sample_type;
}

ImageReader::~ImageReader() = default;

template <class Sample>
std::vector<Sample> ImageReader::decode() {
    const SampleType type = sampleTypeOfC<Sample>();
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
    if (!decoded && !s.input) throw std::logic_error(s.name + ": no decoder for these samples");
    if (!decoded) s.input->decode(type, samples.data());
    s.jpeg.reset();
    s.png.reset();
    s.input.reset();
    s.stdin_copy.reset();
    makeUpright(samples.data(), sizeof(Sample) * header_.channels, s.stored.width, s.stored.height, s.orientation);
    return samples;
}

PackedImage ImageReader::readPacked(bool rows_as_needed) {
    State& s = *state_;
    const bool straight = header_.hasAlpha() && s.alpha_storage == AlphaStorage::Straight;
    if (rows_as_needed && s.codes && s.orientation == 1 && (s.jpeg || (s.png && !s.png->interlaced()))) {
        if (s.decoded) throw std::logic_error("ImageReader::read called twice");
        s.decoded = true;
        s.input.reset();
        // A damaged file fails here, before the run, as a whole read would: read through once.
        // Decoded as it is, a progressive JPEG would hold all of its coefficients until its last
        // row (53 MB for a 13 MP photograph, more than its codes): stored again in one scan.
        if (s.jpeg && s.jpeg->progressive()) s.jpeg = s.jpeg->sequential();
        else if (s.jpeg) JpegDecoder(s.file, s.name).check();
        else PngDecoder(s.file, s.name).check();
        auto rows = std::make_unique<FileRows>(std::move(s.jpeg), std::move(s.png), std::move(s.stdin_copy));
        return PackedImage(header_, std::move(rows), valuesOfCodes(*s.codes == SampleType::UInt8 ? 8 : 16), straight);
    }
    // 8- and 16-bit files are kept as their codes (packed_image.h); anything else as floats.
    if (s.codes == SampleType::UInt8) {
        std::vector<uint8_t> codes = decode<uint8_t>();
        return PackedImage(header_, std::move(codes), valuesOfCodes(8), straight);
    }
    if (s.codes == SampleType::UInt16) {
        std::vector<uint16_t> codes = decode<uint16_t>();
        return PackedImage(header_, std::move(codes), valuesOfCodes(16), straight);
    }
    Image image = header_;
    image.pixels = decode<float>();
    // Interpolating across a NaN or an infinity spreads it over the whole neighbourhood.
    if ((image.sample_type == SampleType::Half || image.sample_type == SampleType::Float) && !allFinite(image.pixels))
        throw UserError(s.name + ": contains NaN or infinite values");
    if (straight) premultiply(image.pixels.data(), image.pixels.size(), image.channels);
    return PackedImage(std::move(image));
}

Image ImageReader::read() { return readPacked().unpack(); }

uint32_t ImageReader::keptSampleBytes() const {
    const std::optional<SampleType> codes = state_->codes;
    return !codes ? uint32_t(sizeof(float)) : codes == SampleType::UInt8 ? 1u : 2u;
}

Image readImage(const std::string& path) { return ImageReader(path).read(); }

}  // namespace ddt
