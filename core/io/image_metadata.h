// What of an input file the output keeps: its metadata, and how each format stores colour
// under alpha (straight or premultiplied), as OIIO 2.4 reads and writes it.
#pragma once

#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <string>
#include <vector>

#include "image.h"

namespace ddt {

// How a file keeps colour under alpha.
enum class AlphaStorage { Straight, Premultiplied };

struct ImageMetadata {
    OIIO::ImageSpec spec;        // the input's spec: its extra attributes are copied to the output
    std::string format_name;     // OIIO's name of the input's format ("png", "openexr", …)
    AlphaStorage alpha_storage;  // how the input file stored colour under alpha
};

// How the file read with `spec` in `format` (OIIO's name) stored colour under alpha.
AlphaStorage inputAlphaStorage(const OIIO::ImageSpec& spec, const std::string& format);
// How a file of `format` is written; TIFF keeps `like`'s choice.
AlphaStorage outputAlphaStorage(const std::string& format, const Image& like);

// Copies `like`'s metadata to `spec`, the output's: resolution scaled with the magnification,
// attributes of the old file dropped, compression settings only to the same format.
void copyMetadata(const Image& like, uint32_t width, uint32_t height, const std::string& format,
                  OIIO::ImageSpec& spec);
// Conventional channel names, so that OpenEXR readers find grey and alpha again.
std::vector<std::string> channelNames(uint32_t channels);

}  // namespace ddt
