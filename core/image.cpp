#include "image.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

namespace ddt {

struct ImageMetadata {
    OIIO::ImageSpec spec;  // the input's spec: format, extra attributes
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

// Formats whose files hold premultiplied colour; every other format gets straight colour.
bool storesPremultiplied(const std::string& format_name) { return format_name == "openexr"; }

void premultiply(std::vector<float>& pixels, uint32_t channels) {
    for (size_t i = 0; i < pixels.size(); i += channels) {
        float alpha = pixels[i + channels - 1];
        for (uint32_t k = 0; k + 1 < channels; ++k) pixels[i + k] *= alpha;
    }
}

void unpremultiply(float* pixels, size_t count, uint32_t channels) {
    for (size_t i = 0; i < count * channels; i += channels) {
        float alpha = pixels[i + channels - 1];
        // Colour under zero alpha is lost by premultiplication; it is written as 0.
        float inverse = alpha > 0.0f ? 1.0f / alpha : 0.0f;
        for (uint32_t k = 0; k + 1 < channels; ++k) pixels[i + k] *= inverse;
    }
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

Image readImage(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw UserError(path + ": no such file");
    if (fs::is_directory(path, ec)) throw UserError(path + ": is a folder, not an image");

    // Ask readers for straight (unassociated) alpha as stored; we premultiply in float.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto input = OIIO::ImageInput::open(path, &config);
    if (!input) throw UserError(path + ": not a readable image (" + firstLine(OIIO::geterror()) + ")");
    const OIIO::ImageSpec& spec = input->spec();
    if (spec.nchannels < 1 || spec.nchannels > 4)
        throw UserError(path + ": " + std::to_string(spec.nchannels) +
                        " channels; ddtup reads grey, grey+alpha, RGB and RGBA images");
    if (spec.depth > 1) throw UserError(path + ": volume images are not supported");

    Image image;
    image.width = uint32_t(spec.width);
    image.height = uint32_t(spec.height);
    image.channels = uint32_t(spec.nchannels);
    image.sample_type = sampleTypeOf(spec.format);
    image.pixels.resize(size_t(image.width) * image.height * image.channels);
    if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data())) {
        std::string message = input->has_error() ? input->geterror() : OIIO::geterror();
        throw UserError(path + ": cannot read pixels (" + firstLine(message) + ")");
    }
    if (image.hasAlpha() && spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0)
        premultiply(image.pixels, image.channels);

    auto metadata = std::make_shared<ImageMetadata>();
    metadata->spec = spec;
    image.metadata = metadata;
    return image;
}

struct ImageWriter::State {
    std::string path;
    std::string temp_path;
    std::unique_ptr<OIIO::ImageOutput> output;
    uint32_t width, height, channels;
    bool straight_alpha;
    uint32_t next_row = 0;
    bool committed = false;
    std::vector<float> scratch;
};

ImageWriter::ImageWriter(const std::string& path, uint32_t width, uint32_t height, const Image& like)
    : state_(std::make_unique<State>()) {
    State& s = *state_;
    s.path = path;
    s.width = width;
    s.height = height;
    s.channels = like.channels;
    s.output = OIIO::ImageOutput::create(path);
    if (!s.output) throw UserError(path + ": cannot write this format (" + firstLine(OIIO::geterror()) + ")");

    OIIO::ImageSpec spec(int(width), int(height), int(like.channels), typeDescOf(like.sample_type));
    if (like.metadata) {
        spec.extra_attribs = like.metadata->spec.extra_attribs;
        // Attributes that describe the input's pixels, not the new image.
        for (const char* stale : {"oiio:UnassociatedAlpha", "Exif:PixelXDimension", "Exif:PixelYDimension",
                                  "oiio:BitsPerSample", "XResolution", "YResolution"})
            spec.erase_attribute(stale);
    }
    if (like.hasAlpha()) spec.alpha_channel = int(like.channels) - 1;
    s.straight_alpha = like.hasAlpha() && !storesPremultiplied(s.output->format_name());
    if (s.straight_alpha) spec.attribute("oiio:UnassociatedAlpha", 1);

    fs::path target(path);
    // A hidden sibling of the output, so the final rename stays within one file system.
    std::string temp_name = target.filename().string();
    temp_name.insert(0, 1, '.');
    temp_name.append(".ddtup-").append(std::to_string(getpid()));
    s.temp_path = (target.parent_path() / temp_name).string();
    if (!s.output->open(s.temp_path, spec)) {
        std::string message = s.output->has_error() ? s.output->geterror() : OIIO::geterror();
        std::error_code ec;
        fs::remove(s.temp_path, ec);
        throw UserError(path + ": cannot write (" + firstLine(message) + ")");
    }
    const OIIO::TypeDesc written = s.output->spec().format;
    if (sampleTypeOf(written) != like.sample_type)
        notes_.push_back(path + ": " + s.output->format_name() + " cannot hold " + sampleTypeName(like.sample_type) +
                         " samples; written as " + sampleTypeName(sampleTypeOf(written)));
}

ImageWriter::~ImageWriter() {
    if (!state_->committed) {
        if (state_->output) state_->output->close();
        std::error_code ec;
        fs::remove(state_->temp_path, ec);
    }
}

void ImageWriter::writeRows(uint32_t y_begin, uint32_t y_end, const float* rows) {
    State& s = *state_;
    if (y_begin != s.next_row || y_end > s.height || y_begin >= y_end) throw std::logic_error("rows out of order");
    const float* data = rows;
    if (s.straight_alpha) {
        size_t count = size_t(y_end - y_begin) * s.width;
        s.scratch.assign(rows, rows + count * s.channels);
        unpremultiply(s.scratch.data(), count, s.channels);
        data = s.scratch.data();
    }
    if (!s.output->write_scanlines(int(y_begin), int(y_end), 0, OIIO::TypeDesc::FLOAT, data))
        throw UserError(s.path + ": cannot write (" + firstLine(s.output->geterror()) + ")");
    s.next_row = y_end;
}

void ImageWriter::commit() {
    State& s = *state_;
    if (s.next_row != s.height) throw std::logic_error("commit before all rows were written");
    if (!s.output->close()) throw UserError(s.path + ": cannot write (" + firstLine(s.output->geterror()) + ")");
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
