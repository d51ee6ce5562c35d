// What of an input file the output keeps: its attributes (resolution, colour space, ICC
// profile, EXIF, text, …) in ddtup's own terms, and how each format stores colour under alpha.
// Only the files that call OpenImageIO convert them to and from its ImageSpec (oiio_metadata.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image.h"
#include "image_attributes.h"

namespace ddt {

// How a file keeps colour under alpha.
enum class AlphaStorage { Straight, Premultiplied };

struct ImageMetadata {
    std::string format_name;     // OIIO's name of the input's format ("png", "openexr", …)
    AlphaStorage alpha_storage;  // how the input file stored colour under alpha
    ImageAttributes attributes;  // of the upright image: no orientation, resolution turned with it
};

// How the file read with `attributes` in `format` (OIIO's name) stored colour under alpha.
AlphaStorage inputAlphaStorage(const ImageAttributes& attributes, const std::string& format);
// How a file of `format` is written; TIFF keeps `like`'s choice.
AlphaStorage outputAlphaStorage(const std::string& format, const Image& like);

// The attributes of the output, a width × height image in `format`, from `like`'s: resolution
// scaled with the magnification, attributes of the old file dropped, compression settings only
// to the same format.
ImageAttributes outputAttributes(const Image& like, uint32_t width, uint32_t height, const std::string& format);
// Conventional channel names, so that OpenEXR readers find grey and alpha again.
std::vector<std::string> channelNames(uint32_t channels);

}  // namespace ddt
