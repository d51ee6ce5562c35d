// ddtup's JPEG writer: its files are byte for byte the ones OpenImageIO 2.4's JPEG writer wrote
// from the same floats and the same attributes (OpenImageIO, linked into the tests, is the
// reference), for grey and RGB, odd sizes, every quality, the density, ICC profiles of one and
// of several chunks, EXIF, IPTC, XMP, a comment, the subsampling choices and floats outside
// [0, 1]; a sink that fails is one exception; ImageWriter's JPEG files match OpenImageIO's too.
#include <catch2/catch.hpp>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <stdlib.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "exif.h"
#include "image_file.h"
#include "image_metadata.h"
#include "iptc.h"
#include "jpeg_encoder.h"
#include "oiio_metadata.h"
#include "png_bytes.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "user_error.h"
#include "xmp.h"

using ddt::ImageAttributes;

namespace {

struct Case {
    uint32_t width = 17, height = 9, channels = 3;
    int quality = 90;
    ImageAttributes attributes;
    std::vector<float> values;  // width · height · channels
};

std::vector<float> randomValues(const Case& c, uint32_t seed = 7) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> values(size_t(c.width) * c.height * c.channels);
    for (float& value : values) value = unit(rng);
    return values;
}

// The file OpenImageIO's writer makes: the attributes and the quality in the spec, as
// ImageWriter gave them, and the floats a row at a time through write_scanlines.
std::string theirs(const Case& c) {
    OIIO::ImageSpec spec(int(c.width), int(c.height), int(c.channels), OIIO::TypeDesc::UINT8);
    ddt::addAttributes(c.attributes, spec);
    spec.attribute("compression", "jpeg:" + std::to_string(c.quality));
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput proxy(bytes);
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create("jpeg");
    REQUIRE(output);
    output->set_ioproxy(&proxy);
    REQUIRE(output->open("memory.jpg", spec));
    REQUIRE(output->write_scanlines(0, int(c.height), 0, OIIO::TypeDesc::FLOAT, c.values.data()));
    REQUIRE(output->close());
    return std::string(bytes.begin(), bytes.end());
}

ddt::JpegMetadata metadataOf(const ImageAttributes& attributes) {
    ddt::JpegMetadata metadata;
    metadata.attributes = ddt::jpegAttributes(attributes);
    metadata.exif = ddt::encodeExifBlock(metadata.attributes);
    metadata.iptc = ddt::encodeIptc(metadata.attributes);
    metadata.xmp = ddt::encodeXmp(metadata.attributes);
    return metadata;
}

// Ours, the rows given in bands of `band` rows.
std::string ours(const Case& c, uint32_t band = 4) {
    std::string bytes;
    ddt::JpegWriter writer({c.width, c.height, c.channels, c.quality}, metadataOf(c.attributes),
                           [&](const uint8_t* data, size_t size) { bytes.append(reinterpret_cast<const char*>(data), size); });
    CHECK(writer.leftOut().empty());
    const size_t row = size_t(c.width) * c.channels;
    for (uint32_t y = 0; y < c.height; y += band) writer.writeRows(c.values.data() + y * row, std::min(band, c.height - y));
    writer.finish();
    return bytes;
}

// The offset of the first marker `code` (0xFFxx) before the image data, or npos.
size_t markerOffset(const std::string& jpeg, uint8_t code) {
    for (size_t at = 2; at + 4 <= jpeg.size() && uint8_t(jpeg[at]) == 0xFF;) {
        if (uint8_t(jpeg[at + 1]) == code) return at;
        if (uint8_t(jpeg[at + 1]) == 0xDA) break;  // start of scan
        at += 2 + (size_t(uint8_t(jpeg[at + 2])) << 8 | uint8_t(jpeg[at + 3]));
    }
    return std::string::npos;
}

// The APP2 markers' offsets, in order.
std::vector<size_t> iccMarkerOffsets(const std::string& jpeg) {
    std::vector<size_t> offsets;
    for (size_t at = 2; at + 4 <= jpeg.size() && uint8_t(jpeg[at + 1]) != 0xDA;) {
        if (uint8_t(jpeg[at + 1]) == 0xE2) offsets.push_back(at);
        at += 2 + (size_t(uint8_t(jpeg[at + 2])) << 8 | uint8_t(jpeg[at + 3]));
    }
    return offsets;
}

// OpenImageIO 2.4 (and 3.1) copies the last of several ICC chunks from the wrong place in the
// profile (at the last chunk's length times its index, not 65519 times it), so the joined
// chunks are not the profile; ddtup writes the profile's true tail there. This puts it in
// OpenImageIO's file, so that the rest is compared byte for byte.
void putTrueIccTail(std::string& jpeg, const std::vector<uint8_t>& profile) {
    const std::vector<size_t> offsets = iccMarkerOffsets(jpeg);
    if (offsets.size() < 2) return;
    const size_t tail = profile.size() - 65519 * (offsets.size() - 1);
    jpeg.replace(offsets.back() + 4 + 14, tail, reinterpret_cast<const char*>(profile.data()) + profile.size() - tail, tail);
}

void requireSameFile(const Case& c) {
    std::string expected = theirs(c);
    if (const ddt::ImageAttribute* icc = c.attributes.find("ICCProfile")) putTrueIccTail(expected, icc->bytes);
    REQUIRE(expected.size() > 100);
    const std::string actual = ours(c);
    REQUIRE(actual.size() == expected.size());
    REQUIRE(actual == expected);
}

std::string bytesOf(const std::vector<uint8_t>& bytes) { return std::string(bytes.begin(), bytes.end()); }

}  // namespace

TEST_CASE("jpeg: grey and RGB, odd sizes and every kind of quality give OpenImageIO's bytes") {
    for (uint32_t channels : {1u, 3u})
        for (auto [width, height] : {std::pair{1u, 1u}, {17u, 9u}, {1000u, 3u}})
            for (int quality : {1, 50, 90, 95, 100}) {
                INFO(width << "×" << height << ", " << channels << " channels, quality " << quality);
                Case c;
                c.width = width;
                c.height = height;
                c.channels = channels;
                c.quality = quality;
                c.values = randomValues(c);
                requireSameFile(c);
            }
}

TEST_CASE("jpeg: the JFIF density follows the resolution, its unit and the pixel aspect ratio as OpenImageIO set it") {
    struct Density {
        float x, y, aspect;
        const char* unit;
    };
    // 0 is "not set". The last ones: an aspect ratio that overrides the resolution, and one
    // alone; a resolution out of the 16-bit range; a unit OpenImageIO does not know.
    const Density densities[] = {{0, 0, 0, nullptr},   {300, 300, 0, "in"},  {118.11f, 0, 0, "cm"}, {0, 72, 0, "none"},
                                 {96, 48, 0, "in"},    {300, 300, 2, "in"},  {0, 0, 0.5f, nullptr}, {0, 0, 2, nullptr},
                                 {0, 100, 2, "in"},    {1e6f, 3, 0, "in"},   {150, 150, 0, "mm"}};
    for (const Density& density : densities) {
        INFO(density.x << ", " << density.y << ", aspect " << density.aspect << ", " << (density.unit ? density.unit : "no unit"));
        Case c;
        if (density.x) c.attributes.set("XResolution", density.x);
        if (density.y) c.attributes.set("YResolution", density.y);
        if (density.aspect) c.attributes.set("PixelAspectRatio", density.aspect);
        if (density.unit) c.attributes.set("ResolutionUnit", std::string(density.unit));
        c.values = randomValues(c);
        requireSameFile(c);
    }
}

TEST_CASE("jpeg: ICC profiles of one chunk and of several, the EXIF block, IPTC, XMP and the comment are OpenImageIO's") {
    Case c;
    c.channels = 3;
    SECTION("an ICC profile in one APP2 chunk") {
        const std::string profile = ddt::test::iccProfile("sRGB");
        ddt::ImageAttribute icc{"ICCProfile", {ddt::AttributeType::Base::UInt8, 1, {}, uint32_t(profile.size())}, {}, {}};
        icc.bytes.assign(profile.begin(), profile.end());
        c.attributes.append(icc);
    }
    SECTION("a profile of 150000 bytes, in three APP2 chunks") {
        ddt::ImageAttribute icc{"ICCProfile", {ddt::AttributeType::Base::UInt8, 1, {}, 150000}, {}, {}};
        std::mt19937 rng(3);
        for (int i = 0; i < 150000; ++i) icc.bytes.push_back(uint8_t(rng()));
        c.attributes.append(icc);
    }
    SECTION("EXIF, GPS and TIFF tags, an sRGB colour space, and EXIF's resolution dropped") {
        c.attributes.set("Make", std::string("Camera Maker"));
        c.attributes.set("Exif:FNumber", 2.8f);
        c.attributes.set("Exif:ISOSpeedRatings", 400);
        c.attributes.set("Exif:DateTimeOriginal", std::string("2024:05:06 07:08:09"));
        c.attributes.set("GPS:Altitude", 123.5f);
        c.attributes.set("exif:XResolution", 72.0f);
        c.attributes.set("oiio:ColorSpace", std::string("sRGB"));
        c.attributes.set("XResolution", 240.0f);
        c.attributes.set("YResolution", 240.0f);
    }
    SECTION("a description (COM, and IPTC's caption) and the attributes IPTC and XMP carry") {
        c.attributes.set("ImageDescription", std::string("A dragonfly on a reed, ×2"));
        c.attributes.set("Copyright", std::string("(c) someone"));
        c.attributes.set("Artist", std::string("someone"));
        c.attributes.set("IPTC:City", std::string("Ghent"));
        c.attributes.set("photoshop:Headline", std::string("Dragonfly"));
    }
    SECTION("chroma subsampling 4:4:4 and progressive") {
        c.attributes.set("jpeg:subsampling", std::string("4:4:4"));
        c.attributes.set("jpeg:progressive", 1);
    }
    SECTION("chroma subsampling 4:2:2") { c.attributes.set("jpeg:subsampling", std::string("4:2:2")); }
    SECTION("chroma subsampling 4:1:1") { c.attributes.set("jpeg:subsampling", std::string("4:1:1")); }
    c.values = randomValues(c);
    requireSameFile(c);
}

TEST_CASE("jpeg: the comment and the ICC chunks hold what the test put in") {
    // Read back independently of both writers: the comment's marker holds the text and its NUL,
    // the three ICC chunks join into the profile.
    Case c;
    c.attributes.set("ImageDescription", std::string("described"));
    ddt::ImageAttribute icc{"ICCProfile", {ddt::AttributeType::Base::UInt8, 1, {}, 140000}, {}, {}};
    for (int i = 0; i < 140000; ++i) icc.bytes.push_back(uint8_t(i * 7));
    c.attributes.append(icc);
    c.values = randomValues(c);
    const std::string jpeg = ours(c);
    const size_t comment = markerOffset(jpeg, 0xFE);
    REQUIRE(comment != std::string::npos);
    CHECK(jpeg.substr(comment + 4, 10) == std::string("described\0", 10));
    std::string joined;
    const std::vector<size_t> offsets = iccMarkerOffsets(jpeg);
    for (size_t i = 0; i < offsets.size(); ++i) {
        const size_t at = offsets[i];
        const size_t length = size_t(uint8_t(jpeg[at + 2])) << 8 | uint8_t(jpeg[at + 3]);
        CHECK(jpeg.substr(at + 4, 14) == std::string("ICC_PROFILE\0", 12) + char(i + 1) + char(offsets.size()));
        joined += jpeg.substr(at + 4 + 14, length - 2 - 14);
    }
    CHECK(offsets.size() == 3);
    CHECK(joined == bytesOf(icc.bytes));
}

TEST_CASE("jpeg: floats below 0, above 1, infinite and NaN become OpenImageIO's codes") {
    // In rows of 17 RGB pixels (51 values: 3 left after groups of 4) the special values land
    // both in groups and in the rest, which OpenImageIO converts otherwise.
    Case c;
    c.height = 30;
    c.quality = 100;
    const float special[] = {-1.0f,   -0.0f, 1.5f,   1e30f, -1e30f, std::numeric_limits<float>::infinity(),
                             -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN(),
                             0.5f / 255.0f, 254.5f / 255.0f, 1.0f + 1e-7f};
    c.values = randomValues(c);
    for (size_t i = 0; i < c.values.size(); i += 3) c.values[i] = special[(i / 3) % std::size(special)];
    requireSameFile(c);
}

TEST_CASE("jpeg: a sink that fails is one exception, from the call that was writing, and the writer is done") {
    Case c;
    c.width = 600;
    c.height = 400;
    c.quality = 100;
    c.values = randomValues(c);  // noise at quality 100: far more than one 64 KiB buffer
    int calls = 0, failures = 0;
    ddt::JpegWriter writer({c.width, c.height, 3, c.quality}, metadataOf(c.attributes), [&](const uint8_t*, size_t) {
        if (++calls == 2) throw std::runtime_error("disk full");
    });
    for (uint32_t y = 0; y < c.height; y += 10) {
        try {
            writer.writeRows(c.values.data() + size_t(y) * c.width * 3, 10);
        } catch (const std::runtime_error& error) {
            CHECK(std::string(error.what()) == "disk full");
            ++failures;
            break;
        }
    }
    CHECK(failures == 1);
    CHECK(calls == 2);
    CHECK_THROWS_AS(writer.finish(), std::logic_error);
    CHECK(calls == 2);
}

// ImageWriter gives the quality, and the input's attributes as outputAttributes kept them.
TEST_CASE("jpeg: ImageWriter's files are OpenImageIO's, at its quality, with the attributes carried over") {
    TempFolder folder;
    ddt::Image image;
    image.width = 23;
    image.height = 11;
    image.channels = 3;
    image.sample_type = ddt::SampleType::UInt8;
    Case c;
    c.width = image.width;
    c.height = image.height;
    c.quality = 80;
    c.values = randomValues(c);
    image.pixels = c.values;
    auto metadata = std::make_shared<ddt::ImageMetadata>();
    metadata->format_name = "png";
    metadata->attributes.set("ImageDescription", std::string("described"));
    metadata->attributes.set("XResolution", 300.0f);
    metadata->attributes.set("YResolution", 300.0f);
    metadata->attributes.set("ResolutionUnit", std::string("in"));
    metadata->attributes.set("oiio:ColorSpace", std::string("sRGB"));  // becomes Exif:ColorSpace
    metadata->attributes.set("exif:XResolution", 300.0f);              // dropped
    image.metadata = metadata;
    ddt::WriteOptions options;
    options.quality = c.quality;
    CHECK(ddt::writeImage(folder / "ours.jpg", image, options).empty());
    c.attributes = ddt::outputAttributes(image, image.width, image.height, "jpeg");
    CHECK(readFile(folder / "ours.jpg") == theirs(c));

    // An image made in memory has no attributes: OpenImageIO still wrote an EXIF block (an
    // empty directory).
    image.metadata = nullptr;
    CHECK(ddt::writeImage(folder / "plain.jpg", image, options).empty());
    c.attributes = {};
    CHECK(readFile(folder / "plain.jpg") == theirs(c));
}

// Injected through the writer's test hook (DDTUP_TEST_WRITE_LIMIT): the failure comes while
// rows are written (the image is far larger than the limit), not at the end.
TEST_CASE("jpeg: a disk that fills up in the middle of the image is one error, and no file stays") {
    TempFolder folder;
    Case c;
    c.width = 600;
    c.height = 400;
    c.values = randomValues(c);
    ddt::Image image;
    image.width = c.width;
    image.height = c.height;
    image.channels = 3;
    image.sample_type = ddt::SampleType::UInt8;
    image.pixels = c.values;
    REQUIRE(theirs(c).size() > 200000);  // twice the limit
    ::setenv("DDTUP_TEST_WRITE_LIMIT", "100000", 1);
    int failures = 0;
    {
        ddt::ImageWriter writer(folder / "full.jpg", c.width, c.height, image);
        for (uint32_t y = 0; y < c.height && failures == 0; y += 20) {
            try {
                writer.writeRows(y, y + 20, image.row(y));
            } catch (const ddt::UserError& error) {
                CHECK(std::string(error.what()) == folder / "full.jpg" + ": No space left on device");
                ++failures;
            }
        }
    }
    ::unsetenv("DDTUP_TEST_WRITE_LIMIT");
    CHECK(failures == 1);
    CHECK(folder.names().empty());
}
