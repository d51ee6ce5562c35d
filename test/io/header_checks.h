// Shared by the PNG and JPEG header tests: OpenImageIO's own reading of a file's attributes
// (the reference), EXIF decoders to give the header readers (OpenImageIO's and ddtup's), an
// entry-by-entry comparison, and an ICC profile with every kind of text
// tag OpenImageIO decodes.
#pragma once

#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/tiffutils.h>

#include <string>

#include "exif.h"
#include "image_attributes.h"
#include "oiio_metadata.h"

namespace ddt::test {

// OpenImageIO's decode_exif as the header readers' DecodeExif (exif_decoding.h): into a spec
// holding the attributes so far, as its readers decode the block.
inline void decodeExifByOpenImageIO(const uint8_t* block, size_t size, ImageAttributes& attributes) {
    OIIO::ImageSpec spec;
    addAttributes(attributes, spec);
    OIIO::decode_exif(OIIO::cspan<uint8_t>(block, size), spec);
    attributes = attributesOf(spec);
}

// ddtup's own decoder (exif.h), the one the reader passes.
inline void decodeExifByDdtup(const uint8_t* block, size_t size, ImageAttributes& attributes) {
    decodeExif(block, size, attributes);
}

// The attributes OpenImageIO's reader gives, opened as ImageReader opens (straight alpha).
inline ImageAttributes attributesByOpenImageIO(const std::string& path) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto input = OIIO::ImageInput::open(path, &config);
    REQUIRE(input);
    return attributesOf(input->spec());
}

inline std::string describe(const ImageAttribute& attribute) {
    std::string text = attribute.name + " (" + std::to_string(int(attribute.type.base)) + "×" +
                       std::to_string(attribute.type.valueCount()) + ")";
    for (const std::string& s : attribute.strings) text += " \"" + s + "\"";
    if (attribute.bytes.size() <= 16)
        for (uint8_t b : attribute.bytes) {
            text += ' ';
            text += std::to_string(b);
        }
    return text;
}

// Same names, types and values in the same order.
inline void requireSameAttributes(const ImageAttributes& ours, const ImageAttributes& theirs) {
    for (size_t i = 0; i < std::max(ours.all().size(), theirs.all().size()); ++i) {
        INFO("attribute " << i);
        REQUIRE(i < ours.all().size());
        REQUIRE(i < theirs.all().size());
        const ImageAttribute& a = ours.all()[i];
        const ImageAttribute& b = theirs.all()[i];
        INFO("ours: " << describe(a) << "\ntheirs: " << describe(b));
        CHECK(a.name == b.name);
        CHECK(a.type == b.type);
        CHECK(a.bytes == b.bytes);
        CHECK(a.strings == b.strings);
    }
}

// An ICC profile (ICC.1 layout) of `colour_space` with a "desc"-type description, a "text"
// copyright, an "mluc" manufacturer name (French and English records) and an unnamed tag,
// and header fields OpenImageIO names (platform, date, flags, intent, creator).
inline std::string iccProfileWithTexts(const char* colour_space) {
    std::string tags, table;
    uint32_t count = 0;
    auto be32 = [](uint32_t v) { return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; };
    auto be16 = [](uint32_t v) { return std::string{char(v >> 8), char(v)}; };
    std::vector<std::pair<std::string, std::string>> entries;
    entries.push_back({"desc", std::string("desc") + std::string(8, '\0') + "Test profile" + std::string(1, '\0')});
    entries.push_back({"cprt", std::string("text") + std::string(4, '\0') + "No copyright" + std::string(1, '\0')});
    std::string mluc = std::string("mluc") + std::string(4, '\0') + be32(2) + be32(12);
    const std::u16string french = u"Fabricant", english = u"Maker \u00e9";
    const uint32_t strings_at = 16 + 2 * 12;
    mluc += std::string("fr") + "FR" + be32(uint32_t(french.size() * 2)) + be32(strings_at);
    mluc += std::string("en") + "US" + be32(uint32_t(english.size() * 2)) + be32(strings_at + uint32_t(french.size() * 2));
    for (char16_t c : french) mluc += be16(c);
    for (char16_t c : english) mluc += be16(c);
    entries.push_back({"dmnd", mluc});
    entries.push_back({"wtpt", std::string("XYZ ") + std::string(16, '\1')});
    const size_t table_end = 128 + 4 + 12 * entries.size();
    for (auto& [signature, data] : entries) {
        while (data.size() % 4) data += '\0';
        table += signature + be32(uint32_t(table_end + tags.size())) + be32(uint32_t(data.size()));
        tags += data;
        ++count;
    }
    std::string header(128, '\0');
    header.replace(0, 4, be32(uint32_t(table_end + tags.size())));
    header.replace(4, 4, "lcms");
    header.replace(8, 4, be32(0x04300000));
    header.replace(12, 4, "mntr");
    header.replace(16, 4, colour_space);
    header.replace(20, 4, "XYZ ");
    header.replace(24, 12, be16(2024) + be16(2) + be16(29) + be16(13) + be16(5) + be16(9));
    header.replace(36, 4, "acsp");
    header.replace(40, 4, "APPL");
    header.replace(44, 4, be32(3));
    header.replace(48, 8, "ddtuTEST");
    header.replace(60, 4, be32(5));
    header.replace(64, 4, be32(1));
    header.replace(68, 12, be32(0xF6D6) + be32(0x10000) + be32(0xD32D));
    header.replace(80, 4, "ddtu");
    return header + be32(count) + table + tags;
}

}  // namespace ddt::test
