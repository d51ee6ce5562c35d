// OpenImageIO's codecs come in a module loaded only when a file needs one (codec_module.h):
// the dynamic loader's own log (LD_DEBUG=files, on stderr) says which libraries a run loaded.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/tiffutils.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "image_file.h"
#include "png_bytes.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

const std::string kSample = ddt::test::testDataPath("crop32_astronaut.png");  // 32×32 RGB, 8-bit

bool loaded(const Run& run, const std::string& library) { return run.err.find(library) != std::string::npos; }

// Runs ddtup with `args` under the loader's log; it succeeds without loading OpenImageIO.
void requireRunWithoutCodecModule(const std::vector<std::string>& args) {
    const Run run = runDdtup(args, {"LD_DEBUG=files"});
    REQUIRE(run.exit_code == 0);
    REQUIRE(loaded(run, "libstdc++"));  // the log names every library loaded: it is on
    CHECK_FALSE(loaded(run, "ddtup-oiio.so"));
    CHECK_FALSE(loaded(run, "libOpenImageIO"));
}

}  // namespace

TEST_CASE("codec module: OpenImageIO is not loaded by --version or --help", "[cli]") {
    for (const char* option : {"--version", "--help"}) {
        INFO(option);
        requireRunWithoutCodecModule({option});
    }
}

TEST_CASE("codec module: a TIFF loads it and reads as its PNG twin does", "[cli]") {
    TempFolder folder;
    const ddt::Image image = ddt::readImage(kSample);
    const std::string tiff = folder / "in.tif";
    ddt::writeImage(tiff, image);
    const std::string from_tiff = folder / "from_tiff.png", from_png = folder / "from_png.png";
    const Run run = runDdtup({tiff, "-s", "2", from_tiff, "-q"}, {"LD_DEBUG=files"});
    REQUIRE(run.exit_code == 0);
    CHECK(loaded(run, "ddtup-oiio.so"));
    CHECK(loaded(run, "libOpenImageIO"));
    REQUIRE(runDdtup({kSample, "-s", "2", from_png, "-q"}).exit_code == 0);
    const ddt::Image a = ddt::readImage(from_tiff), b = ddt::readImage(from_png);
    CHECK(a.width == 64);
    CHECK(a.height == 64);
    CHECK(a.pixels == b.pixels);
}

namespace {

// The data of the first APP13 marker and of the APP1 marker holding XMP, walking the JPEG's
// markers up to its scan; "" where there is none.
struct JpegBlocks {
    std::string app13;
    std::string xmp;
};

JpegBlocks jpegBlocks(const std::string& jpeg) {
    const std::string xmp_name("http://ns.adobe.com/xap/1.0/", 29);
    JpegBlocks blocks;
    size_t at = 2;  // after SOI
    while (at + 4 <= jpeg.size() && uint8_t(jpeg[at]) == 0xFF && uint8_t(jpeg[at + 1]) != 0xDA) {
        const uint8_t marker = uint8_t(jpeg[at + 1]);
        const size_t length = size_t(uint8_t(jpeg[at + 2])) << 8 | uint8_t(jpeg[at + 3]);
        const std::string data = jpeg.substr(at + 4, length - 2);
        if (marker == 0xED && blocks.app13.empty()) blocks.app13 = data;
        if (marker == 0xE1 && data.compare(0, xmp_name.size(), xmp_name) == 0) blocks.xmp = data.substr(xmp_name.size());
        at += 2 + length;
    }
    return blocks;
}

// The IPTC and XMP blocks of `output` are OpenImageIO's encoders' on what OpenImageIO reads
// from `input`.
void checkBlocksOf(const std::string& input, const std::string& output) {
    INFO(input << " to " << output);
    auto reader = OIIO::ImageInput::open(input);
    REQUIRE(reader);
    std::vector<char> iptc;
    OIIO::encode_iptc_iim(reader->spec(), iptc);
    const std::string xmp = OIIO::encode_xmp(reader->spec(), true);
    REQUIRE(!iptc.empty());
    const JpegBlocks blocks = jpegBlocks(readFile(output));
    REQUIRE(blocks.app13.size() >= iptc.size());
    CHECK(blocks.app13.substr(blocks.app13.size() - iptc.size()) == std::string(iptc.begin(), iptc.end()));
    CHECK(blocks.xmp == xmp);
}

}  // namespace

TEST_CASE("codec module: PNG with text and plain JPEG to JPEG do not load it, and the IPTC and XMP are OpenImageIO's", "[cli]") {
    TempFolder folder;
    // The sample with text chunks after its header: what PNG readers turn into ImageDescription,
    // Artist, Copyright and DocumentName, and two that are XMP properties.
    std::string png = readFile(kSample);
    std::string chunks;
    for (const auto& [key, value] : {std::pair<std::string, std::string>{"Title", "A title"},
                                     {"Author", "Ann Author; Bob <bob@example.org>"},
                                     {"Description", "Rock & \"roll\""},
                                     {"Copyright", "(c) 2024 Ann"},
                                     {"GPano:ProjectionType", "equirectangular"},
                                     {"crs:CameraProfile", "Adobe Standard"}})
        chunks += ddt::test::pngChunk("tEXt", key + std::string(1, '\0') + value);
    png.insert(33, chunks);  // after the signature (8) and IHDR (25)
    const std::string input = folder / "text.png";
    std::ofstream(input, std::ios::binary) << png;

    const std::string from_png = folder / "from_png.jpg";
    requireRunWithoutCodecModule({input, "-s", "2", from_png, "-q"});

    checkBlocksOf(input, from_png);
    CHECK(jpegBlocks(readFile(from_png)).xmp.find("GPano:ProjectionType=\"equirectangular\"") != std::string::npos);

    // A JPEG with no IPTC or XMP to JPEG. (One with them is read by OpenImageIO's reader
    // still, image_reader.cpp: its blocks are checked, not what it loads.)
    const std::string plain = folder / "plain.jpg", from_plain = folder / "from_plain.jpg";
    REQUIRE(runDdtup({kSample, plain, "-q"}).exit_code == 0);
    requireRunWithoutCodecModule({plain, "-s", "2", from_plain, "-q"});

    const std::string from_jpeg = folder / "from_jpeg.jpg";
    REQUIRE(runDdtup({from_png, "-s", "2", from_jpeg, "-q"}).exit_code == 0);
    checkBlocksOf(from_png, from_jpeg);
}

TEST_CASE("codec module: PNG to PNG and a turned JPEG with EXIF to PNG do not load it", "[cli]") {
    TempFolder folder;
    // A JPEG with an EXIF block (orientation 6, a camera, an exposure), written by OpenImageIO.
    const ddt::Image image = ddt::readImage(kSample);
    const std::string jpeg = folder / "turned.jpg";
    {
        auto output = OIIO::ImageOutput::create("jpeg");
        OIIO::ImageSpec spec(int(image.width), int(image.height), 3, OIIO::TypeDesc::FLOAT);
        spec.attribute("Orientation", 6);
        spec.attribute("Make", "Camera maker");
        spec.attribute("Exif:ExposureTime", 0.01f);
        REQUIRE(output->open(jpeg, spec));
        REQUIRE(output->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()));
        REQUIRE(output->close());
    }
    for (const std::string& input : {kSample, jpeg}) {
        INFO(input);
        const std::string out = folder / "out.png";
        requireRunWithoutCodecModule({input, "-s", "2", out, "-q"});
        const ddt::Image result = ddt::readImage(out);
        CHECK(result.width == 64);
        CHECK(result.height == 64);
    }
}
