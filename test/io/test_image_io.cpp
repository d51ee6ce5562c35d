// Image files through OpenImageIO: round trips keep channels, depth and values; alpha is held
// premultiplied in memory and stored the way each format expects; metadata is copied.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "image_file.h"
#include "png_bytes.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "temp_files.h"
#include "user_error.h"

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

void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

// Points file descriptor `fd` (standard input or output) at `path` for the test's duration.
class RedirectedStream {
public:
    RedirectedStream(int fd, const std::string& path, int flags) : fd_(fd), saved_(::dup(fd)) {
        const int file = ::open(path.c_str(), flags, 0644);
        REQUIRE(file >= 0);
        ::dup2(file, fd);
        ::close(file);
    }
    ~RedirectedStream() {
        ::dup2(saved_, fd_);
        ::close(saved_);
    }
    RedirectedStream(const RedirectedStream&) = delete;
    RedirectedStream& operator=(const RedirectedStream&) = delete;

private:
    int fd_;
    int saved_;
};

// Sets an environment variable for the test's duration.
class ScopedEnvironment {
public:
    ScopedEnvironment(const char* name, const std::string& value) : name_(name) {
        if (const char* old = ::getenv(name)) old_ = old;
        ::setenv(name, value.c_str(), 1);
    }
    ~ScopedEnvironment() {
        if (old_) ::setenv(name_, old_->c_str(), 1);
        else ::unsetenv(name_);
    }
    ScopedEnvironment(const ScopedEnvironment&) = delete;
    ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

private:
    const char* name_;
    std::optional<std::string> old_;
};

// A 3×2 RGB image whose six pixels are told apart by their red value (in 8-bit steps):
//   a b c       a = 10, b = 20, c = 30
//   d e f       d = 40, e = 50, f = 60
Image makeLetters() {
    Image image;
    image.width = 3;
    image.height = 2;
    image.channels = 3;
    for (uint32_t i = 0; i < 6; ++i) image.pixels.insert(image.pixels.end(), {fromByte(10 * (i + 1)), 0.0f, 0.0f});
    return image;
}

// The red values of an image, row by row, as multiples of 10/255 ("abc/def" for the above).
std::string letters(const Image& image) {
    std::string text;
    for (uint32_t y = 0; y < image.height; ++y) {
        if (y) text += '/';
        for (uint32_t x = 0; x < image.width; ++x)
            text += char('a' - 1 + int(std::lround(image.row(y)[x * image.channels] * 255.0f / 10.0f)));
    }
    return text;
}

void writeWithOrientation(const std::string& path, const Image& image, int orientation) {
    auto output = OIIO::ImageOutput::create(path);
    REQUIRE(output);
    OIIO::ImageSpec spec(int(image.width), int(image.height), int(image.channels), OIIO::TypeDesc::UINT8);
    spec.attribute("Orientation", orientation);
    REQUIRE(output->open(path, spec));
    REQUIRE(output->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()));
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

// Lossy, so only the layout is compared. Every still WebP failed to decode once: OIIO 2.4's
// reader loses its place after the check for a second image (found by the fuzzer's seeds).
TEST_CASE("image: WebP files read back") {
    TempFolder folder;
    for (uint32_t channels : {3u, 4u}) {
        INFO(channels << " channels");
        ddt::writeImage(folder / "still.webp", makeImage(8, 6, channels, SampleType::UInt8));
        const Image back = ddt::readImage(folder / "still.webp");
        CHECK(back.width == 8);
        CHECK(back.height == 6);
        CHECK(back.channels == channels);
    }
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

// Before OIIO sees it: its PNG reader leaks on reading past the end (core/input_check.h).
TEST_CASE("image: a truncated PNG is refused when it is opened") {
    TempFolder folder;
    ddt::writeImage(folder / "whole.png", makeImage(64, 64, 3, SampleType::UInt8));
    std::filesystem::copy_file(folder / "whole.png", folder / "cut.png");
    std::filesystem::resize_file(folder / "cut.png", std::filesystem::file_size(folder / "whole.png") / 2);
    CHECK_THROWS_WITH(ddt::ImageReader(folder / "cut.png"), Catch::Contains("cut.png") && Catch::Contains("truncated PNG"));
}

namespace {

// A little-endian TIFF's first-directory entry for `tag`, turned into a LONG holding `value`.
void setTiffTag(std::string& tiff, uint16_t tag, uint32_t value) {
    auto get = [&](size_t at, int size) {
        uint32_t v = 0;
        for (int i = size - 1; i >= 0; --i) v = v << 8 | uint8_t(tiff[at + i]);
        return v;
    };
    auto put = [&](size_t at, int size, uint32_t v) {
        for (int i = 0; i < size; ++i, v >>= 8) tiff[at + i] = char(v & 0xFF);
    };
    REQUIRE(tiff.compare(0, 4, std::string("II*\0", 4)) == 0);
    const size_t directory = get(4, 4);
    for (size_t entry = directory + 2; entry < directory + 2 + 12 * get(directory, 2); entry += 12)
        if (get(entry, 2) == tag) {
            put(entry + 2, 2, 4);
            put(entry + 8, 4, value);
            return;
        }
    FAIL("no tag " << tag);
}

}  // namespace

// OIIO 2.4's TIFF reader goes on through every strip of a read after one fails, adding a
// message each, and aborts the process past 16 MB of them: here 65536 rows × 3 planes of
// strips that are not in the file (found by the fuzzer). ddtup reads in bands and stops.
TEST_CASE("image: a TIFF claiming far more strips than it holds is refused, not the end of the process") {
    TempFolder folder;
    const std::string path = folder / "planes.tif";
    auto output = OIIO::ImageOutput::create(path);
    OIIO::ImageSpec spec(13, 11, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("tiff:planarconfig", "separate");
    spec.attribute("tiff:RowsPerStrip", 1);
    spec.attribute("compression", "lzw");  // uncompressed, libtiff makes up the missing strips
    const std::vector<uint8_t> pixels(13 * 11 * 3, 100);
    REQUIRE(output->open(path, spec));
    REQUIRE(output->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    REQUIRE(output->close());
    std::string tiff = readFile(path);
    setTiffTag(tiff, 257, 65536);  // ImageLength
    std::ofstream(path, std::ios::binary) << tiff;

    ddt::ImageReader reader(path);
    CHECK(reader.header().height == 65536);
    CHECK_THROWS_WITH(reader.read(), Catch::StartsWith(path + ": truncated or corrupt image"));
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

// Only where the floats go straight to quantiseRow may a caller keep rows as codes
// (app/strip_rows.h): not where alpha is made straight, flattened, or OpenImageIO converts.
TEST_CASE("image: the writer names the codes its rows become only where nothing else happens to them") {
    TempFolder folder;
    const Image rgb = makeImage(4, 4, 3, SampleType::UInt8), rgba = makeImage(4, 4, 4, SampleType::UInt8);
    const Image grey = makeImage(4, 4, 1, SampleType::UInt16);
    ddt::WriteOptions sixteen;
    sixteen.depth = SampleType::UInt16;
    CHECK(ddt::ImageWriter(folder / "a.png", 4, 4, rgb).codeBits() == 8);
    CHECK(ddt::ImageWriter(folder / "b.png", 4, 4, rgb, sixteen).codeBits() == 16);
    CHECK(ddt::ImageWriter(folder / "c.png", 4, 4, grey).codeBits() == 16);
    CHECK(ddt::ImageWriter(folder / "d.jpg", 4, 4, rgb, sixteen).codeBits() == 8);
    CHECK(ddt::ImageWriter(folder / "e.png", 4, 4, rgba).codeBits() == 0);  // straight alpha
    CHECK(ddt::ImageWriter(folder / "f.jpg", 4, 4, rgba).codeBits() == 0);  // flattened onto white
    CHECK(ddt::ImageWriter(folder / "g.tif", 4, 4, rgb).codeBits() == 0);   // OpenImageIO's
    CHECK(folder.names().empty());  // nothing committed
}

TEST_CASE("image: sizes a format cannot hold are refused before opening") {
    CHECK(ddt::checkOutputFormat("x.jpg", 65500, 65500) == "");
    CHECK_THAT(ddt::checkOutputFormat("x.jpg", 65501, 10), Catch::Contains("65500"));
    CHECK_THAT(ddt::checkOutputFormat("x.png", 10, 1000001), Catch::Contains("1000000"));
    CHECK(ddt::checkOutputFormat("x.tif", 70000, 70000) == "");
    CHECK_THAT(ddt::checkOutputFormat("x.unknown", 10, 10), Catch::Contains("extension"));
}

TEST_CASE("image: --depth values parse as sample types") {
    CHECK(ddt::parseSampleType("8") == SampleType::UInt8);
    CHECK(ddt::parseSampleType("16") == SampleType::UInt16);
    CHECK(ddt::parseSampleType("half") == SampleType::Half);
    CHECK(ddt::parseSampleType("float") == SampleType::Float);
    for (const char* bad : {"", "32", "8bit", "Float", "double"}) CHECK(!ddt::parseSampleType(bad));
}

TEST_CASE("image: WriteOptions::depth overrides the input's sample type") {
    TempFolder folder;
    ddt::WriteOptions options;
    options.depth = SampleType::UInt16;
    CHECK(ddt::writeImage(folder / "deep.png", makeImage(4, 4, 3, SampleType::UInt8), options).empty());
    CHECK(ddt::readImage(folder / "deep.png").sample_type == SampleType::UInt16);

    options.depth = SampleType::Half;
    CHECK(ddt::writeImage(folder / "half.exr", makeImage(4, 4, 3, SampleType::UInt16), options).empty());
    CHECK(ddt::readImage(folder / "half.exr").sample_type == SampleType::Half);

    // Still the nearest the format holds, with a note naming the requested type.
    options.depth = SampleType::Float;
    const std::vector<std::string> notes = ddt::writeImage(folder / "f.png", makeImage(4, 4, 3, SampleType::UInt8), options);
    REQUIRE(notes.size() == 1);
    CHECK_THAT(notes[0], Catch::Contains("float") && Catch::Contains("16-bit"));
    CHECK(ddt::readImage(folder / "f.png").sample_type == SampleType::UInt16);
}

TEST_CASE("image: WriteOptions::quality sets the JPEG and WebP quality") {
    TempFolder folder;
    std::mt19937 rng(7);
    Image noise = makeImage(64, 64, 3, SampleType::UInt8);
    for (float& value : noise.pixels) value = fromByte(rng() % 256);
    for (const char* extension : {"jpg", "webp"}) {
        INFO(extension);
        ddt::WriteOptions low, high;
        low.quality = 10;
        high.quality = 95;
        const std::string low_path = folder / (std::string("low.") + extension);
        const std::string high_path = folder / (std::string("high.") + extension);
        ddt::writeImage(low_path, noise, low);
        ddt::writeImage(high_path, noise, high);
        // An ignored quality gives equal sizes; on noise, 10 against 95 is several times
        // smaller, so "half the size" holds with room for other codec versions.
        CHECK(std::filesystem::file_size(low_path) * 2 < std::filesystem::file_size(high_path));
    }
}

TEST_CASE("image: WriteOptions::format overrides the extension and is recognised by content") {
    TempFolder folder;
    ddt::WriteOptions options;
    options.format = "png";
    const Image image = makeImage(5, 3, 3, SampleType::UInt8);
    ddt::writeImage(folder / "picture.data", image, options);
    CHECK(readFile(folder / "picture.data").compare(1, 3, "PNG") == 0);
    requireSameImage(ddt::readImage(folder / "picture.data"), image);

    options.format = "nosuchformat";
    CHECK_THROWS_WITH(ddt::writeImage(folder / "x.png", image, options),
                      Catch::Contains("x.png") && Catch::Contains("nosuchformat"));
}

TEST_CASE("image: \"-\" reads standard input, recognised by content, and leaves no copy") {
    TempFolder folder, temp;
    ScopedEnvironment tmpdir("TMPDIR", temp.path().string());
    const Image image = makeImage(5, 3, 4, SampleType::UInt16);
    ddt::writeImage(folder / "in.png", image);
    {
        RedirectedStream input(STDIN_FILENO, folder / "in.png", O_RDONLY);
        ddt::ImageReader reader(ddt::kStandardStream);
        CHECK(reader.header().width == 5);
        CHECK(temp.names().size() == 1);  // the copy, while the reader needs it
        requireSameImage(reader.read(), image);
    }
    CHECK(temp.names().empty());

    writeBytes(folder / "text", "not an image\n");
    RedirectedStream input(STDIN_FILENO, folder / "text", O_RDONLY);
    CHECK_THROWS_WITH(ddt::ImageReader(ddt::kStandardStream), "standard input: not an image in a format ddtup reads (PNG, JPEG, TIFF, OpenEXR, WebP, BMP, GIF, Targa, PNM, Radiance HDR)");
    CHECK(temp.names().empty());
}

TEST_CASE("image: \"-\" writes standard output in the given format") {
    TempFolder folder, temp;
    ScopedEnvironment tmpdir("TMPDIR", temp.path().string());
    const Image image = makeImage(5, 3, 3, SampleType::UInt8);
    ddt::WriteOptions options;
    options.format = "png";
    {
        RedirectedStream output(STDOUT_FILENO, folder / "out", O_WRONLY | O_CREAT | O_TRUNC);
        ddt::writeImage(ddt::kStandardStream, image, options);
    }
    requireSameImage(ddt::readImage(folder / "out"), image);
    CHECK(temp.names().empty());
    CHECK_THROWS_WITH(ddt::writeImage(ddt::kStandardStream, image), Catch::StartsWith("standard output: ") && Catch::Contains("format"));
}

// /dev/full fails every write with ENOSPC: a real full device, no test hook.
TEST_CASE("image: a full standard output is one error, and no temporary file stays") {
    TempFolder temp;
    ScopedEnvironment tmpdir("TMPDIR", temp.path().string());
    ddt::WriteOptions options;
    options.format = "png";
    RedirectedStream output(STDOUT_FILENO, "/dev/full", O_WRONLY);
    CHECK_THROWS_WITH(ddt::writeImage(ddt::kStandardStream, makeImage(5, 3, 3, SampleType::UInt8), options),
                      "standard output: No space left on device");
    CHECK(temp.names().empty());
}

// Injected through the writer's test hook (DDTUP_TEST_WRITE_LIMIT); the executable tests run a
// real full tmpfs where the machine allows it.
TEST_CASE("image: a write that runs out of space is one error, and no file stays") {
    TempFolder folder;
    ScopedEnvironment limit("DDTUP_TEST_WRITE_LIMIT", "100");
    const Image image = makeImage(64, 64, 3, SampleType::UInt8);
    for (const char* name : {"full.png", "full.jpg", "full.exr", "full.bmp", "full.tga", "full.webp"}) {
        INFO(name);
        CHECK_THROWS_WITH(ddt::writeImage(folder / name, image), folder / name + ": No space left on device");
        CHECK(folder.names().empty());
    }
}

// EXIF orientation n says how the stored pixels turn to be upright (TIFF 6.0, tag 274):
//   stored   2 (mirror)  3 (half turn)  6 (quarter turn clockwise)  8 (anticlockwise)
//   a b c    c b a       f e d          d a                          c f
//   d e f    f e d       c b a          e b                          b e
//                                       f c                          a d
TEST_CASE("image: EXIF orientation is applied, and the output is written upright") {
    TempFolder folder;
    const std::pair<int, const char*> cases[] = {
        {1, "abc/def"}, {2, "cba/fed"}, {3, "fed/cba"}, {4, "def/abc"},
        {5, "ad/be/cf"}, {6, "da/eb/fc"}, {7, "fc/eb/da"}, {8, "cf/be/ad"},
    };
    for (const auto& [orientation, expected] : cases) {
        INFO("orientation " << orientation);
        const std::string path = folder / (std::to_string(orientation) + ".tif");
        writeWithOrientation(path, makeLetters(), orientation);
        ddt::ImageReader reader(path);
        const Image upright = reader.read();
        CHECK(reader.header().width == upright.width);
        CHECK(reader.header().height == upright.height);
        CHECK(letters(upright) == expected);

        for (const char* extension : {"tif", "jpg"}) {
            const std::string output = folder / (std::string("upright.") + extension);
            ddt::writeImage(output, upright);
            CHECK(readRaw(output).spec.get_int_attribute("Orientation", 1) == 1);
        }
    }
}

// What ImageReader::read must return for `raw` (OIIO's own float read of the stored image):
// upright by `orientation` (1 or 6, a quarter turn clockwise: upright (x, y) is stored
// (y, stored height − 1 − x)), colour times alpha where the file stores it straight.
std::vector<float> expectedPixels(const RawFile& raw, int orientation, bool straight) {
    const uint32_t c = uint32_t(raw.spec.nchannels), stored_width = uint32_t(raw.spec.width),
                   stored_height = uint32_t(raw.spec.height);
    const bool turned = orientation == 6;
    const uint32_t width = turned ? stored_height : stored_width, height = turned ? stored_width : stored_height;
    std::vector<float> pixels(raw.pixels.size());
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const uint32_t sx = turned ? y : x, sy = turned ? stored_height - 1 - x : y;
            const float* from = &raw.pixels[(size_t(sy) * stored_width + sx) * c];
            float* to = &pixels[(size_t(y) * width + x) * c];
            const bool alpha = c == 2 || c == 4;
            for (uint32_t k = 0; k < c; ++k) to[k] = straight && alpha && k + 1 < c ? from[k] * from[c - 1] : from[k];
        }
    return pixels;
}

// Writes random samples of `type` through OpenImageIO: straight alpha last where the channel
// count is even, the EXIF `orientation`, and `attribute` set to 1 where one is given.
void writeRandomImage(const std::string& path, uint32_t width, uint32_t height, uint32_t channels, OIIO::TypeDesc type,
                      int orientation, std::mt19937& random, const char* attribute = nullptr) {
    std::vector<float> stored(size_t(width) * height * channels);
    for (float& value : stored) value = float(random() % 1000) / 999.0f;
    auto output = OIIO::ImageOutput::create(path);
    REQUIRE(output);
    OIIO::ImageSpec spec(int(width), int(height), int(channels), type);
    if (channels % 2 == 0) {
        spec.alpha_channel = int(channels) - 1;
        spec.attribute("oiio:UnassociatedAlpha", 1);
    }
    if (attribute) spec.attribute(attribute, 1);
    if (orientation != 1) spec.attribute("Orientation", orientation);
    REQUIRE(output->open(path, spec));
    REQUIRE(output->write_image(OIIO::TypeDesc::FLOAT, stored.data()));
    REQUIRE(output->close());
}

// 8- and 16-bit inputs are kept as their codes and made floats a crop at a time
// (core/image/packed_image.h): every crop must hold exactly the floats OIIO reads, upright and
// premultiplied, and the codes must take a quarter or a half of the floats' bytes.
TEST_CASE("image: inputs kept as 8- or 16-bit codes give crops equal to the file's floats") {
    TempFolder folder;
    struct Case {
        const char* name;
        uint32_t channels;
        OIIO::TypeDesc type;
        int orientation;
        uint32_t kept_bytes;
    };
    const Case cases[] = {
        {"rgba8.png", 4, OIIO::TypeDesc::UINT8, 1, 1},  {"grey-alpha16.png", 2, OIIO::TypeDesc::UINT16, 1, 2},
        {"rgb16.tif", 3, OIIO::TypeDesc::UINT16, 6, 2}, {"photo.jpg", 3, OIIO::TypeDesc::UINT8, 6, 1},
        {"float.exr", 4, OIIO::TypeDesc::FLOAT, 1, 4},
    };
    std::mt19937 random(7);
    for (const Case& test : cases) {
        INFO(test.name);
        const std::string path = folder / test.name;
        const uint32_t width = 37, height = 23;
        writeRandomImage(path, width, height, test.channels, test.type, test.orientation, random);

        const RawFile raw = readRaw(path);
        const bool straight = raw.spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0;
        const std::vector<float> expected = expectedPixels(raw, test.orientation, straight);

        ddt::ImageReader reader(path);
        CHECK(reader.keptSampleBytes() == test.kept_bytes);
        const ddt::PackedImage packed = reader.readPacked();
        const Image& header = packed.header();
        CHECK(packed.bytes() == size_t(width) * height * test.channels * test.kept_bytes);
        for (const ddt::PixelRect rect : {ddt::PixelRect{0, 0, header.width, header.height}, ddt::PixelRect{3, 5, 17, 21},
                                          ddt::PixelRect{header.width - 1, header.height - 2, header.width, header.height}}) {
            INFO("crop " << rect.x0 << "," << rect.y0 << " to " << rect.x1 << "," << rect.y1);
            const Image crop = packed.crop(rect);
            REQUIRE(crop.width == rect.width());
            REQUIRE(crop.height == rect.height());
            for (uint32_t y = 0; y < crop.height; ++y)
                for (size_t i = 0; i < crop.rowFloats(); ++i) {
                    const size_t at = (size_t(rect.y0 + y) * header.width + rect.x0) * test.channels + i;
                    REQUIRE(crop.row(y)[i] == expected[at]);
                }
        }
    }
}

// An input decoded as its rows are needed (ImageReader::readPacked(true)) holds only the rows
// holdRows asks for, and its crops equal those of the input read whole; a file that cannot go
// row by row upright (an EXIF turn, a TIFF; an interlaced PNG: test_png_decoder.cpp) is read
// whole as before.
TEST_CASE("image: JPEG and PNG inputs decoded row by row give the crops of the whole read") {
    TempFolder folder;
    struct Case {
        const char* name;
        uint32_t channels;
        OIIO::TypeDesc type;
        const char* attribute;  // set to 1 on the written spec, or null
        int orientation;
        bool row_by_row;
    };
    const Case cases[] = {
        {"baseline.jpg", 3, OIIO::TypeDesc::UINT8, nullptr, 1, true},
        {"progressive.jpg", 3, OIIO::TypeDesc::UINT8, "jpeg:progressive", 1, true},
        {"grey.jpg", 1, OIIO::TypeDesc::UINT8, nullptr, 1, true},
        {"rgba8.png", 4, OIIO::TypeDesc::UINT8, nullptr, 1, true},
        {"grey-alpha16.png", 2, OIIO::TypeDesc::UINT16, nullptr, 1, true},
        {"turned.jpg", 3, OIIO::TypeDesc::UINT8, nullptr, 6, false},
        {"rgb16.tif", 3, OIIO::TypeDesc::UINT16, nullptr, 1, false},
    };
    std::mt19937 random(11);
    for (const Case& test : cases) {
        INFO(test.name);
        const std::string path = folder / test.name;
        writeRandomImage(path, 41, 67, test.channels, test.type, test.orientation, random, test.attribute);

        const ddt::PackedImage whole = ddt::ImageReader(path).readPacked();
        ddt::PackedImage rows = ddt::ImageReader(path).readPacked(true);
        const Image& header = rows.header();
        const size_t row_bytes = size_t(header.width) * header.channels * (test.type == OIIO::TypeDesc::UINT16 ? 2 : 1);
        CHECK(header.width == whole.header().width);
        CHECK(header.height == whole.header().height);
        CHECK(rows.bytes() == (test.row_by_row ? 0 : whole.bytes()));
        // Strips of 10 rows with crops reaching 4 rows beyond, as tiles do.
        for (uint32_t y = 0; y < header.height; y += 10) {
            const uint32_t y0 = y < 4 ? 0 : y - 4, y1 = std::min(header.height, y + 14);
            rows.holdRows(y0, y1);
            INFO("rows " << y0 << " to " << y1);
            if (test.row_by_row) CHECK(rows.bytes() == (y1 - y0) * row_bytes);
            for (const ddt::PixelRect rect : {ddt::PixelRect{0, y0, header.width, y1}, ddt::PixelRect{5, y0 + 1, 19, y1}}) {
                const Image ours = rows.crop(rect), theirs = whole.crop(rect);
                REQUIRE(ours.pixels.size() == theirs.pixels.size());
                CHECK(ours.pixels == theirs.pixels);
            }
        }
        // Rows once freed do not come back.
        if (test.row_by_row) CHECK_THROWS_AS(rows.holdRows(0, 10), std::logic_error);
    }
    // A file cut short after it was read through (by another program, in the middle of a run)
    // fails when its rows are reached, with an InputError that names it, for the job to pass on.
    const std::string cut = folder / "cut.jpg";
    Image noise = makeImage(300, 300, 3, SampleType::UInt8);
    for (float& value : noise.pixels) value = float(random() % 256) / 255.0f;
    ddt::writeImage(cut, noise);
    // Noise keeps it far larger than what stdio and libjpeg read ahead (4 KiB each): the cut is met.
    REQUIRE(std::filesystem::file_size(cut) > 16 * 4096);
    ddt::PackedImage rows = ddt::ImageReader(cut).readPacked(true);
    rows.holdRows(0, 10);
    std::filesystem::resize_file(cut, std::filesystem::file_size(cut) / 2);
    try {
        rows.holdRows(0, rows.header().height);
        FAIL("the rows of a file cut short were decoded");
    } catch (const ddt::InputError& error) {
        CHECK_THAT(error.what(), Catch::StartsWith(cut + ": truncated or corrupt image ("));
    }
}

TEST_CASE("image: of several images in a file the first is read, with a note") {
    TempFolder folder;
    const Image first = makeImage(6, 4, 3, SampleType::UInt8), second = makeImage(6, 4, 3, SampleType::UInt8);
    for (const char* name : {"pages.tif", "frames.gif"}) {
        INFO(name);
        auto output = OIIO::ImageOutput::create(folder / name);
        REQUIRE(output->supports("multiimage"));
        std::vector<OIIO::ImageSpec> specs(3, OIIO::ImageSpec(6, 4, 3, OIIO::TypeDesc::UINT8));
        REQUIRE(output->open(folder / name, 3, specs.data()));
        for (int i = 0; i < 3; ++i) {
            if (i) REQUIRE(output->open(folder / name, specs[size_t(i)], OIIO::ImageOutput::AppendSubimage));
            std::vector<float> pixels(6 * 4 * 3, float(i) / 2.0f);
            if (i == 0) pixels = first.pixels;
            REQUIRE(output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
        }
        REQUIRE(output->close());

        ddt::ImageReader reader(folder / name);
        REQUIRE(reader.notes().size() == 1);
        CHECK(reader.notes()[0] == folder / name + ": has more than one image (pages or frames); using the first");
        const Image image = reader.read();
        CHECK(image.width == 6);
        if (std::string(name) == "pages.tif") CHECK(image.pixels == first.pixels);
    }
    ddt::writeImage(folder / "single.tif", first);
    CHECK(ddt::ImageReader(folder / "single.tif").notes().empty());
}

TEST_CASE("image: a header over 2^28 pixels is refused before anything is allocated") {
    TempFolder folder;
    writeBytes(folder / "huge.png", ddt::test::pngClaiming(100000, 100000));
    CHECK_THROWS_WITH(ddt::ImageReader(folder / "huge.png"),
                      folder / "huge.png" + ": image is 100000×100000 pixels; ddtup reads at most 268435456 pixels (16384×16384)");
    writeBytes(folder / "just_over.png", ddt::test::pngClaiming(16385, 16384));
    CHECK_THROWS_WITH(ddt::ImageReader(folder / "just_over.png"), Catch::Contains("16385×16384"));
    // The limit itself is allowed: the header is accepted (the pixels are not there to read).
    writeBytes(folder / "limit.png", ddt::test::pngClaiming(16384, 16384));
    CHECK(ddt::ImageReader(folder / "limit.png").header().width == 16384);
}

TEST_CASE("image: empty files, folders and 0×0 headers are refused with the reason") {
    TempFolder folder;
    writeBytes(folder / "empty.png", "");
    CHECK_THROWS_WITH(ddt::ImageReader(folder / "empty.png"), folder / "empty.png" + ": empty file (0 bytes)");
    std::filesystem::create_directory(folder / "dir.png");
    CHECK_THROWS_WITH(ddt::ImageReader(folder / "dir.png"), folder / "dir.png" + ": is a folder, not an image file");
    writeBytes(folder / "zero.png", ddt::test::pngClaiming(0, 0));
    CHECK_THROWS_WITH(ddt::ImageReader(folder / "zero.png"), Catch::StartsWith(folder / "zero.png" + ": "));
}

TEST_CASE("image: NaN or infinite samples are refused after decoding") {
    TempFolder folder;
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                      -std::numeric_limits<float>::infinity()}) {
        Image image = makeImage(4, 4, 3, SampleType::Float);
        image.pixels[7] = bad;
        ddt::writeImage(folder / "bad.exr", image);
        ddt::ImageReader reader(folder / "bad.exr");
        CHECK_THROWS_WITH(reader.read(), folder / "bad.exr" + ": contains NaN or infinite values");
    }
}

TEST_CASE("image: a temporary file is removed unless released") {
    TempFolder folder;
    std::string kept;
    {
        ddt::TempFile removed(folder.path().string(), "t");
        CHECK(std::filesystem::exists(removed.path()));
    }
    CHECK(folder.names().empty());
    {
        ddt::TempFile renamed(folder.path().string(), "t");
        std::filesystem::rename(renamed.path(), folder / "final");
        renamed.release();
    }
    CHECK(folder.names() == std::set<std::string>{"final"});
    CHECK_THROWS_AS(ddt::TempFile(folder / "missing", "t"), std::system_error);
}
