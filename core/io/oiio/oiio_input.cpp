#include "oiio_input.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>

#include "oiio_codec.h"
#include "oiio_metadata.h"
#include "user_error.h"

namespace ddt {

namespace {

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

// Moves to image `index`; false where there is none. A failed seek past the last image leaves
// a message, dropped here.
bool seekQuietly(OIIO::ImageInput& input, int index) {
    QuietStderr quiet;
    const bool found = input.seek_subimage(index, 0);
    globalError();
    codecError(input);
    return found;
}

// Whether the file holds a second image (a page, a frame; MIP levels do not count). Only
// one seek: counting them all decodes every frame of an animated GIF (0.85 s for 300 frames
// of 512², measured), for a note.
bool hasSeveralImages(OIIO::ImageInput& input) {
    // OIIO 2.4's WebP reader loses its frame when a seek fails (libwebp clears the iterator,
    // and the seek back to 0 finds the reader already there), and a still image then fails
    // to decode. Only animations hold more than one image, and its spec says which are.
    if (input.format_name() == std::string("webp")) return input.spec().get_int_attribute("oiio:Movie") != 0;
    const bool several = seekQuietly(input, 1);
    seekQuietly(input, 0);
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
    if (spec.tile_width) return input.read_image(input.current_subimage(), 0, 0, spec.nchannels, request, pixels);
    const int band = decodeBandRows(spec);
    const size_t row_bytes = size_t(spec.width) * spec.nchannels * type.size();
    for (int y = 0; y < spec.height; y += band) {
        const int end = std::min(spec.height, y + band);
        if (!input.read_scanlines(input.current_subimage(), 0, spec.y + y, spec.y + end, 0, 0, spec.nchannels, request,
                                  static_cast<char*>(pixels) + size_t(y) * row_bytes) ||
            input.has_error())
            return false;
    }
    return true;
}

class OiioInput final : public CodecInput {
public:
    OiioInput(std::unique_ptr<OIIO::ImageInput> input, std::string name) : input_(std::move(input)), name_(std::move(name)) {
        const bool several = hasSeveralImages(*input_);
        describe();
        stored_.several_images = several;
    }

    const StoredImage& stored() const override { return stored_; }

    bool seekImage(uint32_t index) override {
        const bool found = seekQuietly(*input_, int(index));
        if (found) describe();
        return found;
    }

    void decode(SampleType type, void* samples) override {
        bool ok;
        {
            QuietStderr quiet;
            ok = decodePixels(*input_, typeDescOf(type), samples);
        }
        // libjpeg fills a truncated file with grey and OIIO returns success, but records the error.
        if (!ok || input_->has_error())
            throw UserError(name_ + ": truncated or corrupt image (" + firstLine(codecError(*input_)) + ")");
    }

private:
    void describe() {
        const OIIO::ImageSpec& spec = input_->spec();
        if (spec.deep) throw UserError(name_ + ": deep images are not supported");
        if (spec.depth > 1) throw UserError(name_ + ": volume images are not supported");
        if (spec.width < 1 || spec.height < 1) throw UserError(name_ + ": the image has no pixels");
        stored_.width = uint32_t(spec.width);
        stored_.height = uint32_t(spec.height);
        stored_.channels = uint32_t(spec.nchannels);
        stored_.sample_type = sampleTypeOf(spec.format);
        // Signed and mixed per-channel types are converted to floats as they are read.
        stored_.keeps_codes =
            spec.channelformats.empty() && (spec.format == OIIO::TypeDesc::UINT8 || spec.format == OIIO::TypeDesc::UINT16);
        stored_.format_name = input_->format_name();
        stored_.attributes = attributesOf(spec);
        stored_.channel_layout_problem = checkChannelLayout(spec);
    }

    std::unique_ptr<OIIO::ImageInput> input_;
    std::string name_;
    StoredImage stored_;
};

}  // namespace

std::unique_ptr<CodecInput> openOiioInput(const std::string& file, const std::string& name, const ImageFormat& format) {
    // Ask readers for straight alpha as stored; premultiplying in float loses nothing.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::ImageInput> input;
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
    return std::make_unique<OiioInput>(std::move(input), name);
}

}  // namespace ddt
