#include "image_metadata.h"

#include <set>

namespace ddt {

// ---- Alpha: what OIIO 2.4 actually does, measured per format (see test_image_io.cpp).
// Asked with "oiio:UnassociatedAlpha", the PNG, Targa and TIFF (unassociated) readers return
// straight colour and say so in that attribute. The BMP reader returns its straight colour as
// stored without saying so. OpenEXR and associated TIFF come back as stored, premultiplied,
// which is also OIIO's convention for every other reader.
AlphaStorage inputAlphaStorage(const ImageAttributes& attributes, const std::string& format) {
    if (attributes.getInt("oiio:UnassociatedAlpha", 0) != 0) return AlphaStorage::Straight;
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

// Attributes of the input that describe its old pixels, layout or file, not the new image.
const char* const kStaleAttributes[] = {
    "oiio:UnassociatedAlpha", "tiff:UnassociatedAlpha", "oiio:BitsPerSample", "Exif:PixelXDimension",
    "Exif:PixelYDimension", "tiff:RowsPerStrip", "tiff:PhotometricInterpretation", "tiff:Compression",
    "tiff:PlanarConfiguration", "planarconfig", "oiio:subimages", "thumbnail_width", "thumbnail_height",
    "thumbnail_nchannels", "thumbnail_image",
};

// The input's attributes. Resolution (dots per inch) scales with the magnification, so that a
// print keeps its size; compression settings are per format and copied only to the same one.
ImageAttributes outputAttributes(const Image& like, uint32_t width, uint32_t height, const std::string& format) {
    const ImageAttributes& from = like.metadata->attributes;
    ImageAttributes attributes = from;
    for (const char* stale : kStaleAttributes) attributes.erase(stale);
    if (like.metadata->format_name != format) {
        attributes.erase("compression");
        attributes.erase("CompressionQuality");
    }
    if (like.width && like.height) {
        if (const std::optional<float> x = from.findFloat("XResolution"))
            attributes.set("XResolution", *x * float(width) / float(like.width));
        if (const std::optional<float> y = from.findFloat("YResolution"))
            attributes.set("YResolution", *y * float(height) / float(like.height));
    }
    return attributes;
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

}  // namespace ddt
