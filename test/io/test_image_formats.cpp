// The formats ddtup reads and writes, and their file extensions: OpenImageIO's own list is
// the reference (core/io/image_formats.cpp holds a copy, so that naming one needs no OpenImageIO).
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "image_formats.h"

TEST_CASE("formats: each format's extensions are OpenImageIO's, and name it in any case") {
    const auto& theirs = OIIO::get_extension_map();
    for (const ddt::ImageFormat& format : ddt::imageFormats()) {
        INFO(format.oiio_name);
        std::vector<std::string> ours;
        std::istringstream words(format.extensions);
        for (std::string word; words >> word;) ours.push_back(word);
        REQUIRE(theirs.count(format.oiio_name));
        CHECK(ours == theirs.at(format.oiio_name));
        for (std::string extension : ours) {
            CHECK(ddt::formatOfExtension(extension) == &format);
            std::transform(extension.begin(), extension.end(), extension.begin(), ::toupper);
            CHECK(ddt::formatOfExtension("." + extension) == &format);
        }
    }
    CHECK(ddt::formatOfExtension("dds") == nullptr);  // OpenImageIO's, not ddtup's
    CHECK(ddt::formatOfExtension("pn") == nullptr);   // part of one
    CHECK(ddt::formatOfExtension("png jpg") == nullptr);
    CHECK(ddt::formatOfExtension("") == nullptr);
    CHECK(ddt::formatOfExtension(".") == nullptr);
}
