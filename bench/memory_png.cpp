#include "memory_png.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <stdexcept>

namespace bench {

namespace {

// OIIO picks the format from this name's extension; nothing is read from or written to it.
const char* const kFormatName = "in-memory.png";

}  // namespace

PngInMemory encodePng(const ddt::Image& image) {
    PngInMemory png{{}, image.width, image.height, image.channels};
    OIIO::Filesystem::IOVecOutput proxy(png.bytes);
    auto output = OIIO::ImageOutput::create(kFormatName, &proxy);
    const OIIO::ImageSpec spec(int(image.width), int(image.height), int(image.channels), OIIO::TypeDesc::UINT8);
    if (!output || !output->open(kFormatName, spec) ||
        !output->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()) || !output->close())
        throw std::runtime_error("cannot encode a PNG in memory: " + (output ? output->geterror() : OIIO::geterror()));
    return png;
}

ddt::Image decodePng(const PngInMemory& png) {
    OIIO::Filesystem::IOMemReader proxy(png.bytes.data(), png.bytes.size());
    auto input = OIIO::ImageInput::open(kFormatName, nullptr, &proxy);
    if (!input) throw std::runtime_error("cannot decode a PNG in memory: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = input->spec();
    ddt::Image image;
    image.width = uint32_t(spec.width);
    image.height = uint32_t(spec.height);
    image.channels = uint32_t(spec.nchannels);
    image.sample_type = ddt::SampleType::UInt8;
    image.pixels.resize(size_t(image.width) * image.height * image.channels);
    if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
        throw std::runtime_error("cannot decode a PNG in memory: " + input->geterror());
    return image;
}

}  // namespace bench
