#include "protocol.h"
#include "image_file.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>

namespace bench {

namespace {

// OIIO reads the wrapped buffer only; resize never writes its source.
OIIO::ImageBuf wrapForReading(const ddt::Image& image) {
    OIIO::ImageSpec spec(int(image.width), int(image.height), int(image.channels), OIIO::TypeDesc::FLOAT);
    return OIIO::ImageBuf(spec, const_cast<float*>(image.pixels.data()));
}

ddt::Image imageLike(const ddt::Image& like, uint32_t width, uint32_t height) {
    ddt::Image image;
    image.width = width;
    image.height = height;
    image.channels = like.channels;
    image.sample_type = ddt::SampleType::UInt8;
    image.pixels.resize(size_t(width) * height * like.channels);
    return image;
}

ddt::Image colourOnly(const ddt::Image& image) {
    ddt::Image colour = imageLike(image, image.width, image.height);
    colour.channels = image.channels - 1;
    colour.pixels.resize(size_t(image.width) * image.height * colour.channels);
    for (size_t i = 0, pixels = size_t(image.width) * image.height; i < pixels; ++i)
        for (uint32_t c = 0; c < colour.channels; ++c)
            colour.pixels[i * colour.channels + c] = image.pixels[i * image.channels + c];
    return colour;
}

}  // namespace

ddt::Image loadOriginal(const std::string& path, std::string& note) {
    ddt::Image image = ddt::readImage(path);
    note.clear();
    if (!image.hasAlpha()) return image;
    note = path + ": alpha channel dropped; colour compared as premultiplied (over black)";
    return colourOnly(image);
}

ddt::Image cropCentred(const ddt::Image& image, uint32_t width, uint32_t height) {
    assert(width <= image.width && height <= image.height);
    const uint32_t x0 = (image.width - width) / 2, y0 = (image.height - height) / 2;
    ddt::Image crop = imageLike(image, width, height);
    for (uint32_t y = 0; y < height; ++y) {
        const float* from = image.row(y0 + y) + size_t(x0) * image.channels;
        std::copy(from, from + crop.rowFloats(), crop.row(y));
    }
    return crop;
}

ddt::Image cropToMultiple(const ddt::Image& image, uint32_t factor) {
    return cropCentred(image, image.width / factor * factor, image.height / factor * factor);
}

ddt::Image makeLowRes(const ddt::Image& original, uint32_t factor) {
    ddt::Image image = original;
    for (uint32_t f = factor; f > 1; f /= 2) {
        assert(f % 2 == 0 && image.width % 2 == 0 && image.height % 2 == 0);
        image = resizeWithFilter(image, "triangle", image.width / 2, image.height / 2);
    }
    return roundedTo8Bit(image);
}

ddt::Image resizeWithFilter(const ddt::Image& image, const std::string& filter, uint32_t width, uint32_t height) {
    const OIIO::ImageBuf source = wrapForReading(image);
    OIIO::ImageBuf resized(OIIO::ImageSpec(int(width), int(height), int(image.channels), OIIO::TypeDesc::FLOAT));
    if (!OIIO::ImageBufAlgo::resize(resized, source, filter))
        throw std::runtime_error("resize with filter " + filter + " failed: " + resized.geterror());
    ddt::Image result = imageLike(image, width, height);
    if (!resized.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, result.pixels.data()))
        throw std::runtime_error("resize with filter " + filter + ": cannot read the result: " + resized.geterror());
    return result;
}

ddt::Image roundedTo8Bit(const ddt::Image& image) {
    ddt::Image rounded = image;
    for (float& v : rounded.pixels) v = float(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)) / 255.0f;
    return rounded;
}

}  // namespace bench
