// readPngHeader against OpenImageIO's PNG reader: every attribute, entry by entry, for the
// bundled PNGs and for files written here with each chunk OpenImageIO reads.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "header_checks.h"
#include "image_file.h"
#include "image_metadata.h"
#include "exif.h"
#include "oiio_metadata.h"
#include "png_bytes.h"
#include "png_header.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;
using ddt::test::pngChunk;

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

std::string be32(uint32_t v) { return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; }

std::string deflated(const std::string& bytes) {
    uLongf size = compressBound(uLong(bytes.size()));
    std::string out(size, '\0');
    REQUIRE(compress(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(bytes.data()), uLong(bytes.size())) == Z_OK);
    out.resize(size);
    return out;
}

// `png` with `chunks` after its IHDR chunk (which ends at byte 33).
std::string withChunks(const std::string& png, const std::string& chunks) { return png.substr(0, 33) + chunks + png.substr(33); }

std::string text(const std::string& key, const std::string& value) { return pngChunk("tEXt", key + '\0' + value); }
std::string iccp(const std::string& profile) { return pngChunk("iCCP", std::string("profile") + '\0' + '\0' + deflated(profile)); }
std::string chrm(const std::vector<uint32_t>& values) {
    std::string data;
    for (uint32_t v : values) data += be32(v);
    return pngChunk("cHRM", data);
}

// An EXIF block (TIFF structure) with an orientation, a resolution, a date and a colour space.
std::string exifBlock(int orientation) {
    ddt::ImageAttributes attributes;
    attributes.set("Orientation", int32_t(orientation));
    attributes.set("XResolution", 300.0f);
    attributes.set("YResolution", 150.0f);
    attributes.set("ResolutionUnit", std::string("in"));
    attributes.set("DateTime", std::string("2024:01:02 03:04:05"));
    attributes.set("Exif:ColorSpace", int32_t(1));
    attributes.set("Exif:FNumber", 2.8f);
    return ddt::encodeExif(attributes);
}

// ImageMagick's "Raw profile type exif" text: "exif", the byte count, the bytes in hex.
std::string hexExifText(const std::string& block) {
    const std::string bytes = std::string("Exif\0\0", 6) + block;
    std::string text = "\nexif\n" + std::to_string(bytes.size()) + "\n";
    const char* digits = "0123456789abcdef";
    for (size_t i = 0; i < bytes.size(); ++i) {
        text += digits[uint8_t(bytes[i]) >> 4];
        text += digits[uint8_t(bytes[i]) & 15];
        if (i % 36 == 35) text += '\n';
    }
    return text;
}

void requireSameAsOpenImageIO(const std::string& path) {
    INFO(path);
    const std::optional<ddt::PngHeader> ours = ddt::readPngHeader(path, path, ddt::test::decodeExifByOpenImageIO);
    REQUIRE(ours);
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto input = OIIO::ImageInput::open(path, &config);
    REQUIRE(input);
    const OIIO::ImageSpec& spec = input->spec();
    CHECK(ours->width == uint32_t(spec.width));
    CHECK(ours->height == uint32_t(spec.height));
    CHECK(ours->channels == uint32_t(spec.nchannels));
    CHECK(ours->bits == spec.format.size() * 8);
    ddt::test::requireSameAttributes(ours->attributes, ddt::attributesOf(spec));
    // With the EXIF decoder the reader passes.
    const std::optional<ddt::PngHeader> reader_s = ddt::readPngHeader(path, path, ddt::test::decodeExifByDdtup);
    REQUIRE(reader_s);
    ddt::test::requireSameAttributes(reader_s->attributes, ddt::attributesOf(spec));
}

}  // namespace

TEST_CASE("png header: the bundled and the test data PNGs read as OpenImageIO reads them", "[io]") {
    std::vector<fs::path> files;
    for (const char* folder : {"/work/shared/data/images", DDTUP_TEST_DATA})
        if (fs::is_directory(folder))
            for (const auto& entry : fs::recursive_directory_iterator(folder))
                if (entry.path().extension() == ".png") files.push_back(entry.path());
    REQUIRE(!files.empty());
    for (const fs::path& file : files) requireSameAsOpenImageIO(file.string());
}

TEST_CASE("png header: each chunk OpenImageIO reads gives its attributes, names, types and order", "[io]") {
    TempFolder folder;
    const std::string rgb = readBytes(ddt::test::testDataPath("two_2x1_rgb.png"));
    const std::string grey = readBytes(ddt::test::testDataPath("step8_gray.png"));
    const std::vector<uint32_t> srgb_chrm = {31270, 32900, 64000, 33000, 30000, 60000, 15000, 6000};
    const std::vector<uint32_t> wide_chrm = {31270, 32900, 73470, 26530, 11590, 82640, 15000, 1800};
    const std::string block = exifBlock(6);
    struct Case {
        const char* name;
        const std::string* base;
        std::string chunks;
    };
    const Case cases[] = {
        {"plain", &rgb, ""},
        {"linear", &rgb, pngChunk("gAMA", be32(100000))},
        {"gamma22", &rgb, pngChunk("gAMA", be32(45455))},
        {"gamma18", &rgb, pngChunk("gAMA", be32(55556))},
        {"gamma_zero", &rgb, pngChunk("gAMA", be32(0))},
        {"srgb", &rgb, pngChunk("sRGB", std::string(1, '\0'))},
        {"srgb_gamma", &rgb, pngChunk("gAMA", be32(45455)) + pngChunk("sRGB", std::string(1, '\1'))},
        {"chrm_srgb", &rgb, pngChunk("gAMA", be32(45455)) + chrm(srgb_chrm)},
        {"chrm_wide", &rgb, pngChunk("gAMA", be32(45455)) + chrm(wide_chrm)},
        {"chrm_only", &rgb, chrm(srgb_chrm)},
        {"iccp", &rgb, iccp(ddt::test::iccProfile("RGB "))},
        {"iccp_texts", &rgb, pngChunk("gAMA", be32(45455)) + iccp(ddt::test::iccProfileWithTexts("RGB "))},
        {"iccp_grey", &grey, iccp(ddt::test::iccProfileWithTexts("GRAY"))},
        {"iccp_mismatch", &rgb, iccp(ddt::test::iccProfile("GRAY"))},
        {"phys_metre", &rgb, pngChunk("pHYs", be32(2835) + be32(3780) + '\1')},
        {"phys_none", &rgb, pngChunk("pHYs", be32(1) + be32(2) + '\0')},
        {"time", &rgb, pngChunk("tIME", std::string("\x07\xe8\x02\x1d\x0d\x05\x09", 7))},
        {"texts", &rgb,
         text("Description", "a test") + text("Author", "ddtup") + text("Title", "Two pixels") + text("Comment", "one") +
             text("Software", "png_header test") + text("comment", "two")},
        {"ztxt", &rgb, pngChunk("zTXt", std::string("Comment") + '\0' + '\0' + deflated("compressed comment"))},
        {"itxt", &rgb,
         pngChunk("iTXt", std::string("Title") + '\0' + '\0' + '\0' + "fr" + '\0' + "Titre" + '\0' + "Deux pixels \xc3\xa9") +
             pngChunk("iTXt", std::string("Notes") + '\0' + '\1' + '\0' + "" + '\0' + "" + '\0' + deflated("compressed"))},
        {"exif", &rgb, pngChunk("eXIf", block)},
        {"exif_time", &rgb, pngChunk("tIME", std::string("\x07\xe8\x02\x1d\x0d\x05\x09", 7)) + pngChunk("eXIf", block)},
        {"exif_text", &rgb, text("Raw profile type exif", hexExifText(exifBlock(3)))},
        {"exif_phys", &grey, pngChunk("pHYs", be32(2835) + be32(2835) + '\1') + pngChunk("eXIf", exifBlock(8))},
        {"everything", &rgb,
         pngChunk("gAMA", be32(45455)) + chrm(wide_chrm) + iccp(ddt::test::iccProfileWithTexts("RGB ")) +
             pngChunk("pHYs", be32(3000) + be32(3000) + '\1') + pngChunk("tIME", std::string("\x07\xe8\x0c\x1f\x17\x3b\x3b", 7)) +
             text("Description", "all of them") + pngChunk("eXIf", block)},
    };
    for (const Case& c : cases) {
        const std::string path = (folder.path() / (std::string(c.name) + ".png")).string();
        writeBytes(path, withChunks(*c.base, c.chunks));
        requireSameAsOpenImageIO(path);
    }
}

TEST_CASE("png header: XMP is left to OpenImageIO, and the reader then gives its attributes", "[io]") {
    TempFolder folder;
    const std::string path = (folder.path() / "xmp.png").string();
    const std::string xmp = "<x:xmpmeta xmlns:x='adobe:ns:meta/'><rdf:RDF xmlns:rdf='http://www.w3.org/1999/02/22-rdf-syntax-ns#'>"
                            "<rdf:Description xmlns:tiff='http://ns.adobe.com/tiff/1.0/' tiff:Make='ddtup'/></rdf:RDF></x:xmpmeta>";
    writeBytes(path, withChunks(readBytes(ddt::test::testDataPath("two_2x1_rgb.png")),
                                pngChunk("iTXt", std::string("XML:com.adobe.xmp") + '\0' + '\0' + '\0' + '\0' + '\0' + xmp)));
    CHECK(!ddt::readPngHeader(path, path, ddt::test::decodeExifByOpenImageIO));
    const ddt::ImageReader reader(path);
    ddt::test::requireSameAttributes(reader.header().metadata->attributes, ddt::test::attributesByOpenImageIO(path));
}

TEST_CASE("png header: a damaged header is refused in OpenImageIO's words", "[io]") {
    TempFolder folder;
    const std::string path = (folder.path() / "zero.png").string();
    writeBytes(path, ddt::test::pngClaiming(0, 0));
    CHECK(ddt::test::userErrorOf([&] { ddt::readPngHeader(path, "zero.png", ddt::test::decodeExifByOpenImageIO); }) ==
          "zero.png: not a readable PNG image (PNG read error: Invalid IHDR data)");
}
