// Image files through OpenImageIO: round trips keep channels, depth and values; alpha is held
// premultiplied in memory and stored the way each format expects; metadata is copied.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <string>
#include <vector>

#include "image.h"
#include "temp_folder.h"

using ddt::Image;
using ddt::SampleType;

namespace {

// An 8-bit or 16-bit sample k as OIIO converts it to float: k * (1 / max), not k / max.
float fromByte(uint32_t k) { return float(k) * (1.0f / 255.0f); }
float fromShort(uint32_t k) { return float(k) * (1.0f / 65535.0f); }

// Levels a sample type holds exactly: 8/16-bit steps, or multiples of 1/64 (exact in half),
// with values above 1 for the float types, which hold linear light.
float level(SampleType type, uint32_t k) {
    switch (type) {
        case SampleType::UInt8:
            return fromByte(k % 256);
        case SampleType::UInt16:
            return fromShort((k * 257 + 3) % 65536);
        default:
            return float(k % 160) / 64.0f;
    }
}

// Opaque, half transparent, transparent and nearly transparent alpha values of `type`.
float alphaLevel(SampleType type, uint32_t k) {
    const bool byte = type == SampleType::UInt8, half = type == SampleType::UInt16;
    const float levels[4] = {1.0f, byte ? fromByte(128) : half ? fromShort(32768) : 0.5f, 0.0f,
                             byte ? fromByte(3) : half ? fromShort(3) : 0.125f};
    return levels[k % 4];
}

// A small image of varied values, premultiplied like the reader makes them.
Image makeImage(uint32_t width, uint32_t height, uint32_t channels, SampleType type) {
    Image image;
    image.width = width;
    image.height = height;
    image.channels = channels;
    image.sample_type = type;
    image.pixels.resize(size_t(width) * height * channels);
    for (uint32_t i = 0; i < width * height; ++i) {
        float* pixel = &image.pixels[size_t(i) * channels];
        const float alpha = image.hasAlpha() ? alphaLevel(type, i) : 1.0f;
        for (uint32_t c = 0; c + (image.hasAlpha() ? 1 : 0) < channels; ++c) pixel[c] = level(type, i * 37 + c * 91) * alpha;
        if (image.hasAlpha()) pixel[channels - 1] = alpha;
    }
    return image;
}

void requireSameImage(const Image& a, const Image& b) {
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    REQUIRE(a.channels == b.channels);
    REQUIRE(a.sample_type == b.sample_type);
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        INFO("sample " << i);
        REQUIRE(a.pixels[i] == b.pixels[i]);
    }
}

// What the file holds, read with OIIO directly: straight colour where the file stores it so.
struct RawFile {
    OIIO::ImageSpec spec;
    std::vector<float> pixels;
};

RawFile readRaw(const std::string& path) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto input = OIIO::ImageInput::open(path, &config);
    REQUIRE(input);
    RawFile raw{input->spec(), {}};
    raw.pixels.resize(size_t(raw.spec.width) * raw.spec.height * raw.spec.nchannels);
    REQUIRE(input->read_image(0, 0, 0, raw.spec.nchannels, OIIO::TypeDesc::FLOAT, raw.pixels.data()));
    return raw;
}

// Writes 2×1 RGBA pixels as given, with OIIO directly, for files made by other programs.
void writeRaw(const std::string& path, OIIO::TypeDesc type, const std::vector<float>& pixels, bool unassociated) {
    auto output = OIIO::ImageOutput::create(path);
    REQUIRE(output);
    OIIO::ImageSpec spec(2, 1, 4, type);
    spec.alpha_channel = 3;
    if (unassociated) spec.attribute("oiio:UnassociatedAlpha", 1);
    REQUIRE(output->open(path, spec));
    REQUIRE(output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    REQUIRE(output->close());
}

void requireRoundTrip(const std::string& name, uint32_t channels, SampleType type) {
    TempFolder folder;
    const Image image = makeImage(5, 3, channels, type);
    const std::vector<std::string> notes = ddt::writeImage(folder / name, image);
    CHECK(notes.empty());
    requireSameImage(ddt::readImage(folder / name), image);
}

}  // namespace

TEST_CASE("image: grey PNG round trip keeps channels, depth and values") {
    requireRoundTrip("grey.png", 1, SampleType::UInt8);
}

TEST_CASE("image: grey+alpha PNG round trip keeps channels, depth and values") {
    requireRoundTrip("grey_alpha.png", 2, SampleType::UInt8);
}

TEST_CASE("image: RGB PNG round trip keeps channels, depth and values") {
    requireRoundTrip("rgb.png", 3, SampleType::UInt8);
}

TEST_CASE("image: RGBA PNG round trip keeps channels, depth and values") {
    requireRoundTrip("rgba.png", 4, SampleType::UInt8);
}

TEST_CASE("image: 16-bit PNG round trip keeps depth") {
    requireRoundTrip("rgba16.png", 4, SampleType::UInt16);
    requireRoundTrip("grey16.png", 1, SampleType::UInt16);
}

TEST_CASE("image: 16-bit TIFF round trip keeps depth") {
    requireRoundTrip("rgba16.tif", 4, SampleType::UInt16);
    requireRoundTrip("rgb16.tif", 3, SampleType::UInt16);
}

TEST_CASE("image: 8-bit TIFF, Targa and BMP round trips keep values") {
    requireRoundTrip("rgba.tif", 4, SampleType::UInt8);
    requireRoundTrip("grey_alpha.tif", 2, SampleType::UInt8);
    requireRoundTrip("rgba.tga", 4, SampleType::UInt8);
    requireRoundTrip("rgba.bmp", 4, SampleType::UInt8);
}

TEST_CASE("image: float EXR round trip keeps depth and values") {
    requireRoundTrip("rgba.exr", 4, SampleType::Float);
    requireRoundTrip("grey.exr", 1, SampleType::Float);
}

TEST_CASE("image: half EXR round trip keeps depth and values") {
    requireRoundTrip("rgba_half.exr", 4, SampleType::Half);
    requireRoundTrip("grey_alpha_half.exr", 2, SampleType::Half);
}

// OIIO's PNG reader, asked for unassociated alpha, returns the stored straight colour and says
// so; we premultiply in float. Its writer, told the colour is straight, stores it as is.
TEST_CASE("image: PNG holds straight colour, memory holds it premultiplied") {
    TempFolder folder;
    const std::vector<float> straight = {fromByte(200), fromByte(100), fromByte(50), fromByte(128), 0.5f, 0.5f, 0.5f, 0.0f};
    writeRaw(folder / "other.png", OIIO::TypeDesc::UINT8, straight, true);

    const Image image = ddt::readImage(folder / "other.png");
    REQUIRE(image.channels == 4);
    CHECK(image.pixels[0] == fromByte(200) * fromByte(128));
    CHECK(image.pixels[2] == fromByte(50) * fromByte(128));
    CHECK(image.pixels[3] == fromByte(128));
    CHECK(image.pixels[4] == 0.0f);  // colour under zero alpha is lost

    ddt::writeImage(folder / "ours.png", image);
    const RawFile raw = readRaw(folder / "ours.png");
    CHECK(raw.pixels[0] == fromByte(200));
    CHECK(raw.pixels[1] == fromByte(100));
    CHECK(raw.pixels[2] == fromByte(50));
    CHECK(raw.pixels[3] == fromByte(128));
}

// OpenEXR stores premultiplied colour; the reader returns it as stored and must not multiply
// by alpha again, and the writer must not divide.
TEST_CASE("image: EXR colour is premultiplied once, not twice") {
    TempFolder folder;
    const std::vector<float> premultiplied = {0.25f, 0.125f, 0.5f, 0.5f, 0.0f, 0.0f, 0.0f, 0.0f};
    writeRaw(folder / "other.exr", OIIO::TypeDesc::HALF, premultiplied, false);

    const Image image = ddt::readImage(folder / "other.exr");
    CHECK(image.sample_type == SampleType::Half);
    CHECK(image.pixels == premultiplied);

    ddt::writeImage(folder / "ours.exr", image);
    CHECK(readRaw(folder / "ours.exr").pixels == premultiplied);
}

// TIFF can hold either; an associated-alpha TIFF (OIIO's default) stays premultiplied, so it is
// neither multiplied again on reading nor rewritten differently.
TEST_CASE("image: associated-alpha TIFF stays premultiplied") {
    TempFolder folder;
    const std::vector<float> premultiplied = {fromByte(100), fromByte(50), fromByte(25), fromByte(128), 0, 0, 0, 0};
    writeRaw(folder / "other.tif", OIIO::TypeDesc::UINT8, premultiplied, false);

    const Image image = ddt::readImage(folder / "other.tif");
    CHECK(image.pixels == premultiplied);

    ddt::writeImage(folder / "ours.tif", image);
    const RawFile raw = readRaw(folder / "ours.tif");
    CHECK(raw.spec.get_int_attribute("tiff:UnassociatedAlpha", 0) == 0);
    CHECK(raw.pixels == premultiplied);
}

// OIIO's BMP reader returns the straight colour BMP files hold without saying so.
TEST_CASE("image: BMP alpha is read as straight colour") {
    TempFolder folder;
    writeRaw(folder / "other.bmp", OIIO::TypeDesc::UINT8, {1.0f, fromByte(100), 0.0f, fromByte(128), 0, 0, 0, 1}, true);
    const Image image = ddt::readImage(folder / "other.bmp");
    CHECK(image.pixels[0] == fromByte(128));
    CHECK(image.pixels[1] == fromByte(100) * fromByte(128));
    CHECK(image.pixels[3] == fromByte(128));
}

TEST_CASE("image: float into PNG is written as 16-bit with a note") {
    TempFolder folder;
    const std::vector<std::string> notes = ddt::writeImage(folder / "f.png", makeImage(4, 4, 3, SampleType::Float));
    REQUIRE(notes.size() == 1);
    CHECK_THAT(notes[0], Catch::Contains("f.png") && Catch::Contains("float") && Catch::Contains("16-bit"));
    CHECK(ddt::readImage(folder / "f.png").sample_type == SampleType::UInt16);
}

TEST_CASE("image: 16-bit into JPEG is written as 8-bit with a note") {
    TempFolder folder;
    const std::vector<std::string> notes = ddt::writeImage(folder / "x.jpg", makeImage(4, 4, 3, SampleType::UInt16));
    REQUIRE(notes.size() == 1);
    CHECK_THAT(notes[0], Catch::Contains("16-bit") && Catch::Contains("8-bit"));
    CHECK(ddt::readImage(folder / "x.jpg").sample_type == SampleType::UInt8);
}

TEST_CASE("image: alpha into JPEG is flattened onto white with a note") {
    TempFolder folder;
    Image image = makeImage(8, 8, 4, SampleType::UInt8);
    for (size_t i = 0; i < image.pixels.size(); i += 4) {
        image.pixels[i] = image.pixels[i + 1] = image.pixels[i + 2] = image.pixels[i + 3] = 0.0f;  // transparent
    }
    const std::vector<std::string> notes = ddt::writeImage(folder / "flat.jpg", image);
    REQUIRE(notes.size() == 1);
    CHECK_THAT(notes[0], Catch::Contains("alpha") && Catch::Contains("white"));
    const Image flat = ddt::readImage(folder / "flat.jpg");
    CHECK(flat.channels == 3);
    for (float value : flat.pixels) CHECK(value == 1.0f);
}

TEST_CASE("image: grey into a format without grey is written as RGB with a note") {
    TempFolder folder;
    const std::vector<std::string> notes = ddt::writeImage(folder / "g.bmp", makeImage(4, 4, 2, SampleType::UInt8));
    REQUIRE(notes.size() == 1);
    CHECK_THAT(notes[0], Catch::Contains("RGBA"));
    CHECK(ddt::readImage(folder / "g.bmp").channels == 4);
}

TEST_CASE("image: metadata is copied, attributes of the old pixels are not") {
    TempFolder folder;
    auto output = OIIO::ImageOutput::create(folder / "in.tif");
    OIIO::ImageSpec spec(4, 2, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("ImageDescription", "a test card");
    spec.attribute("Artist", "ddtup tests");
    spec.attribute("XResolution", 72.0f);
    spec.attribute("YResolution", 72.0f);
    spec.attribute("ResolutionUnit", "in");
    spec.attribute("Exif:PixelXDimension", 4);
    std::vector<float> pixels(4 * 2 * 3, 0.5f);
    REQUIRE(output->open(folder / "in.tif", spec));
    REQUIRE(output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    REQUIRE(output->close());

    Image image = ddt::readImage(folder / "in.tif");
    for (const char* name : {"out.tif", "out.png"}) {
        INFO(name);
        ddt::ImageWriter writer(folder / name, 12, 6, image);  // magnified 3×
        std::vector<float> rows(12 * 6 * 3, 0.5f);
        writer.writeRows(0, 6, rows.data());
        writer.commit();
        const OIIO::ImageSpec written = readRaw(folder / name).spec;
        CHECK(written.get_string_attribute("ImageDescription") == "a test card");
        CHECK(written.get_string_attribute("Artist") == "ddtup tests");
        // A print keeps its size: dots per inch follow the magnification.
        CHECK(written.get_float_attribute("XResolution") == Approx(216.0f).epsilon(1e-3));  // PNG: pixels per metre
        CHECK(written.get_float_attribute("YResolution") == Approx(216.0f).epsilon(1e-3));
        CHECK(written.get_int_attribute("Exif:PixelXDimension", 0) != 4);
    }
}

TEST_CASE("image: a truncated PNG is refused when its pixels are read") {
    TempFolder folder;
    ddt::writeImage(folder / "whole.png", makeImage(64, 64, 3, SampleType::UInt8));
    std::filesystem::copy_file(folder / "whole.png", folder / "cut.png");
    std::filesystem::resize_file(folder / "cut.png", std::filesystem::file_size(folder / "whole.png") / 2);

    ddt::ImageReader reader(folder / "cut.png");  // the header is intact
    CHECK(reader.header().width == 64);
    CHECK_THROWS_WITH(reader.read(), Catch::Contains("cut.png"));
}

TEST_CASE("image: channel layouts other than grey, grey+alpha, RGB, RGBA are refused") {
    TempFolder folder;
    auto output = OIIO::ImageOutput::create(folder / "rg.exr");
    OIIO::ImageSpec spec(2, 2, 2, OIIO::TypeDesc::HALF);
    spec.channelnames = {"R", "G"};
    std::vector<float> pixels(2 * 2 * 2, 0.5f);
    REQUIRE(output->open(folder / "rg.exr", spec));
    REQUIRE(output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    REQUIRE(output->close());
    CHECK_THROWS_AS(ddt::readImage(folder / "rg.exr"), ddt::UserError);
    CHECK_THROWS_WITH(ddt::readImage(folder / "rg.exr"), Catch::Contains("rg.exr") && Catch::Contains("R, G"));
}

TEST_CASE("image: an abandoned or failed write leaves no file") {
    TempFolder folder;
    const Image image = makeImage(4, 4, 3, SampleType::UInt8);
    {
        ddt::ImageWriter writer(folder / "abandoned.png", 4, 4, image);
        writer.writeRows(0, 2, image.pixels.data());
    }
    CHECK(folder.names().empty());
    CHECK_THROWS_AS(ddt::ImageWriter(folder / "missing/x.png", 4, 4, image), ddt::UserError);
    CHECK(folder.names().empty());
}

TEST_CASE("image: sizes a format cannot hold are refused before opening") {
    CHECK(ddt::checkOutputFormat("x.jpg", 65500, 65500) == "");
    CHECK_THAT(ddt::checkOutputFormat("x.jpg", 65501, 10), Catch::Contains("65500"));
    CHECK_THAT(ddt::checkOutputFormat("x.png", 10, 1000001), Catch::Contains("1000000"));
    CHECK(ddt::checkOutputFormat("x.tif", 70000, 70000) == "");
    CHECK_THAT(ddt::checkOutputFormat("x.unknown", 10, 10), Catch::Contains("extension"));
}
