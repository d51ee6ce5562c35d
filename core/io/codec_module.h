// OpenImageIO's codecs, for the image formats ddtup does not read or write itself, in a module
// of their own (ddtup-oiio.so, built from core/io/oiio/) that is loaded the first time a file
// needs one. A PNG or JPEG job's process then holds none of OpenImageIO's ~260 shared libraries:
// they took 128 MB of `ddtup --version`'s 134 MB and 0.21 s of its start-up (issue 33).
// This header speaks only ddtup's types, so that nothing outside the module sees OpenImageIO's.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "image.h"
#include "image_attributes.h"
#include "image_formats.h"
#include "output_layout.h"

namespace ddt {

// An image file's header as stored: before any EXIF orientation turns it.
struct StoredImage {
    uint32_t width = 0, height = 0, channels = 0;
    SampleType sample_type = SampleType::UInt8;
    bool keeps_codes = false;           // unsigned 8- or 16-bit samples in every channel, kept as such
    std::string format_name;            // OpenImageIO's name of the format ("png", "tiff", …)
    ImageAttributes attributes;         // in the file's order, the orientation among them
    bool several_images = false;        // pages or frames beyond the first
    std::string channel_layout_problem;  // "" for grey, grey+alpha, RGB or RGBA with alpha last
};

// A file opened by a codec: its header now, its pixels on request.
class CodecInput {
public:
    virtual ~CodecInput() = default;
    // The current image (the first, until seekImage).
    virtual const StoredImage& stored() const = 0;
    // Moves to the image `index` (a page of a TIFF); false when there is none.
    virtual bool seekImage(uint32_t index) = 0;
    // Every sample of the current image as stored, channels interleaved, as `type`: UInt8 and
    // UInt16 give the codes themselves (keeps_codes), Float the codec's values. Throws
    // UserError("NAME: truncated or corrupt image (…)").
    virtual void decode(SampleType type, void* samples) = 0;
};

// A file being written by a codec, rows in order.
class CodecOutput {
public:
    virtual ~CodecOutput() = default;
    // The sample type the file stores: the one asked for, or the nearest the format holds.
    virtual SampleType written() const = 0;
    // Rows [y_begin, y_end) in the stored layout (OutputLayout::out_channels floats a pixel).
    virtual void writeRows(uint32_t y_begin, uint32_t y_end, const float* rows) = 0;
    // Closes the file; throws UserError when anything failed to reach it.
    virtual void finish() = 0;
};

// What an output file is to hold.
struct OutputRequest {
    std::string temp_path;  // the file to write (renamed into place by the caller)
    std::string name;       // for messages
    const ImageFormat* format = nullptr;
    uint32_t width = 0, height = 0;
    SampleType wanted = SampleType::UInt8;
    ImageAttributes attributes;
};

class CodecModule {
public:
    virtual ~CodecModule() = default;
    // Opens `file` with the reader of `format` (named `name` in messages) and reads its header.
    // Throws UserError for a file that reader refuses, a deep or volume image, or no pixels.
    virtual std::unique_ptr<CodecInput> openInput(const std::string& file, const std::string& name,
                                                  const ImageFormat& format) = 0;
    // Whether the format's writer keeps an alpha channel.
    virtual bool writesAlpha(const ImageFormat& format) = 0;
    // Opens the output as `request` asks. A format without grey gets RGB (`layout` says so;
    // the note is the caller's), one without the wanted sample type its nearest.
    virtual std::unique_ptr<CodecOutput> openOutput(const OutputRequest& request, OutputLayout& layout) = 0;
    // The threads the codecs may use.
    virtual void setThreads(unsigned count) = 0;
};

// The module, loaded on the first call (and given the thread count set before). Throws
// std::runtime_error naming the paths tried when it cannot be loaded.
CodecModule& codecModule();

// The threads OpenImageIO's codecs may use (its own pool, apart from parallel.h's); kept until
// the module is loaded, so that setting it does not load it.
void setCodecThreads(unsigned count);

}  // namespace ddt
