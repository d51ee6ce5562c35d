// JpegDecoder against OpenImageIO's JPEG reader, which calls the same libjpeg-turbo: every code
// equal for the layouts photographs come in, the EXIF block and ICC profile as written, and
// bad files refused in one line that names them.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/tiffutils.h>

// jpeglib.h needs FILE and size_t declared before it.
#include <cstdio>
#include <jpeglib.h>

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <memory>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "image_file.h"
#include "jpeg_decoder.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

using ddt::JpegDecoder;
namespace fs = std::filesystem;

// The photo crop (300 × 200) as 8-bit codes: `channels` 1 takes its green.
std::vector<uint8_t> photoCodes(uint32_t channels, uint32_t width, uint32_t height) {
    const ddt::Image photo = ddt::test::photoCrop();
    std::vector<uint8_t> codes;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x)
            for (uint32_t c = 0; c < channels; ++c) {
                const float value = photo.pixels[(size_t(y) * photo.width + x) * photo.channels + (channels == 1 ? 1 : c)];
                codes.push_back(uint8_t(value * 255.0f + 0.5f));
            }
    return codes;
}

// Writes codes as a JPEG file through OpenImageIO, with `settings` applied to its spec.
void writeJpeg(const std::string& path, uint32_t width, uint32_t height, uint32_t channels,
               const std::vector<uint8_t>& codes, const std::function<void(OIIO::ImageSpec&)>& settings = {}) {
    OIIO::ImageSpec spec(int(width), int(height), int(channels), OIIO::TypeDesc::UINT8);
    if (settings) settings(spec);
    auto output = OIIO::ImageOutput::create(path);
    REQUIRE(output);
    REQUIRE(output->open(path, spec));
    REQUIRE(output->write_image(OIIO::TypeDesc::UINT8, codes.data()));
    REQUIRE(output->close());
}

// The codes OpenImageIO's reader gives for the file.
std::vector<uint8_t> codesByOpenImageIO(const std::string& path) {
    auto input = OIIO::ImageInput::open(path);
    REQUIRE(input);
    const OIIO::ImageSpec& spec = input->spec();
    std::vector<uint8_t> codes(size_t(spec.width) * spec.height * spec.nchannels);
    REQUIRE(input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, codes.data()));
    return codes;
}

std::vector<uint8_t> codesByDecoder(const std::string& path) {
    JpegDecoder decoder(path, path);
    REQUIRE(decoder.decodable());
    std::vector<uint8_t> codes(size_t(decoder.width()) * decoder.height() * decoder.channels());
    decoder.decode(codes.data());
    return codes;
}

// The codes by decodeRows in runs of 1, 2, 3 … rows; `sequential`: from the decoder's
// sequential() copy, which must be a single scan.
std::vector<uint8_t> codesInRuns(const std::string& path, bool sequential) {
    std::unique_ptr<JpegDecoder> decoder = std::make_unique<JpegDecoder>(path, path);
    if (sequential) {
        decoder = decoder->sequential();
        CHECK_FALSE(decoder->progressive());
    }
    const size_t row_bytes = size_t(decoder->width()) * decoder->channels();
    std::vector<uint8_t> codes(row_bytes * decoder->height());
    for (uint32_t y = 0, run = 1; y < decoder->height(); y += run, ++run) {
        run = std::min(run, decoder->height() - y);
        decoder->decodeRows(run, codes.data() + y * row_bytes);
    }
    return codes;
}

// A flat JPEG written by libjpeg itself, with nothing but an ICC profile if one is given:
// OpenImageIO writes no CMYK files, always an EXIF block, and no profile longer than one marker.
void writeByLibjpeg(const std::string& path, uint32_t width, uint32_t height, J_COLOR_SPACE space,
                    const std::vector<uint8_t>& profile = {}) {
    jpeg_compress_struct info{};
    jpeg_error_mgr errors{};
    info.err = jpeg_std_error(&errors);
    jpeg_create_compress(&info);
    std::FILE* file = std::fopen(path.c_str(), "wb");
    REQUIRE(file);
    jpeg_stdio_dest(&info, file);
    info.image_width = width;
    info.image_height = height;
    info.input_components = space == JCS_CMYK ? 4 : space == JCS_GRAYSCALE ? 1 : 3;
    info.in_color_space = space;
    jpeg_set_defaults(&info);
    jpeg_start_compress(&info, TRUE);
    if (!profile.empty()) jpeg_write_icc_profile(&info, profile.data(), unsigned(profile.size()));
    std::vector<uint8_t> row(size_t(width) * info.input_components, 100);
    while (info.next_scanline < height) {
        JSAMPROW rows[] = {row.data()};
        jpeg_write_scanlines(&info, rows, 1);
    }
    jpeg_finish_compress(&info);
    jpeg_destroy_compress(&info);
    std::fclose(file);
}

}  // namespace

TEST_CASE("jpeg decoder: every code equals OpenImageIO's for grey, chroma subsamplings, progressive files and odd sizes",
          "[io]") {
    TempFolder folder;
    struct Case {
        const char* name;
        uint32_t channels, width, height;
        std::function<void(OIIO::ImageSpec&)> settings;
    };
    const Case cases[] = {
        {"grey", 1, 300, 200, {}},
        {"420", 3, 300, 200, [](OIIO::ImageSpec& s) { s.attribute("jpeg:subsampling", "4:2:0"); }},
        {"422 odd", 3, 97, 61, [](OIIO::ImageSpec& s) { s.attribute("jpeg:subsampling", "4:2:2"); }},
        {"444 q30", 3, 300, 200,
         [](OIIO::ImageSpec& s) {
             s.attribute("jpeg:subsampling", "4:4:4");
             s.attribute("Compression", "jpeg:30");
         }},
        {"progressive", 3, 255, 129, [](OIIO::ImageSpec& s) { s.attribute("jpeg:progressive", 1); }},
        {"progressive grey", 1, 300, 200, [](OIIO::ImageSpec& s) { s.attribute("jpeg:progressive", 1); }},
        {"progressive 420 odd", 3, 97, 61,
         [](OIIO::ImageSpec& s) {
             s.attribute("jpeg:progressive", 1);
             s.attribute("jpeg:subsampling", "4:2:0");
         }},
        {"one pixel", 3, 1, 1, {}},
    };
    for (const Case& c : cases) {
        INFO(c.name);
        const std::string path = folder / (std::string(c.name) + ".jpg");
        writeJpeg(path, c.width, c.height, c.channels, photoCodes(c.channels, c.width, c.height), c.settings);
        JpegDecoder header(path, path);
        CHECK(header.width() == c.width);
        CHECK(header.height() == c.height);
        CHECK(header.channels() == c.channels);
        const std::vector<uint8_t> ours = codesByDecoder(path), theirs = codesByOpenImageIO(path);
        REQUIRE(ours.size() == theirs.size());
        CHECK(ours == theirs);
        CHECK(header.progressive() == (std::string(c.name).find("progressive") == 0));
        // A row at a time, and in uneven runs, as a PackedImage asks for them: the same codes.
        CHECK(codesInRuns(path, false) == theirs);
        // Stored again sequentially first: one scan, and still the same codes.
        CHECK(codesInRuns(path, true) == theirs);
    }
}

// check() reads a file without decoding its pixels, so that a file whose rows are decoded
// later fails before the run begins: it must refuse exactly the files decode() refuses.
TEST_CASE("jpeg decoder: check() refuses exactly the damaged files decode() refuses", "[io]") {
    TempFolder folder;
    const std::string whole = folder / "whole.jpg", damaged = folder / "damaged.jpg";
    writeJpeg(whole, 300, 200, 3, photoCodes(3, 300, 200));
    std::ifstream in(whole, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t scan = bytes.rfind("\xff\xda");  // the entropy-coded data follows the last SOS marker
    REQUIRE(scan != std::string::npos);
    std::mt19937 random(17);
    int refused = 0;
    for (int i = 0; i < 60; ++i) {
        std::string copy = bytes;
        const size_t at = scan + 20 + random() % (bytes.size() - scan - 22);
        copy[at] = char(copy[at] ^ (1 << (random() % 8)));
        if (i % 10 == 9) copy.resize(scan + 20 + random() % (bytes.size() - scan - 20));  // cut short too
        std::ofstream(damaged, std::ios::binary | std::ios::trunc) << copy;
        INFO("damage " << i << " at byte " << at);
        std::vector<uint8_t> codes(300 * 200 * 3);
        const std::string by_decode = ddt::test::userErrorOf([&] { JpegDecoder(damaged, "d.jpg").decode(codes.data()); });
        const std::string by_check = ddt::test::userErrorOf([&] { JpegDecoder(damaged, "d.jpg").check(); });
        CHECK(by_check.empty() == by_decode.empty());
        refused += !by_decode.empty();
    }
    // Most single flipped bits break a Huffman code or a marker; some only change a coefficient.
    CHECK(refused >= 10);
    JpegDecoder intact(whole, "whole.jpg");
    CHECK_NOTHROW(intact.check());
}

TEST_CASE("jpeg decoder: the EXIF block and the ICC profile come out as written", "[io]") {
    TempFolder folder;
    const std::string path = folder / "tagged.jpg";
    std::vector<uint8_t> profile(1000);
    for (size_t i = 0; i < profile.size(); ++i) profile[i] = uint8_t(i * 7 + i / 251);
    writeJpeg(path, 64, 48, 3, photoCodes(3, 64, 48), [&](OIIO::ImageSpec& s) {
        s.attribute("Orientation", 6);
        s.attribute("Make", "ddtup test camera");
        s.attribute("ICCProfile", OIIO::TypeDesc(OIIO::TypeDesc::UINT8, int(profile.size())), profile.data());
    });
    const JpegDecoder decoder(path, path);
    CHECK(decoder.iccProfile() == profile);
    // OpenImageIO's own EXIF parser reads the block back.
    REQUIRE(!decoder.exif().empty());
    OIIO::ImageSpec exif;
    REQUIRE(OIIO::decode_exif(OIIO::cspan<uint8_t>(decoder.exif().data(), decoder.exif().size()), exif));
    CHECK(exif.get_int_attribute("Orientation") == 6);
    CHECK(exif.get_string_attribute("Make") == "ddtup test camera");

    // A profile longer than one APP2 marker holds (65 519 bytes) comes in chunks, joined in order.
    std::vector<uint8_t> long_profile(150000);
    for (size_t i = 0; i < long_profile.size(); ++i) long_profile[i] = uint8_t(i * 13 + i / 65519);
    const std::string chunked = folder / "chunked.jpg";
    writeByLibjpeg(chunked, 8, 8, JCS_RGB, long_profile);
    const JpegDecoder three_chunks(chunked, chunked);
    CHECK(three_chunks.iccProfile() == long_profile);
    CHECK(three_chunks.exif().empty());

    const std::string plain = folder / "plain.jpg";
    writeByLibjpeg(plain, 8, 8, JCS_GRAYSCALE);
    const JpegDecoder untagged(plain, plain);
    CHECK(untagged.exif().empty());
    CHECK(untagged.iccProfile().empty());
}

TEST_CASE("jpeg decoder: a file that is not a JPEG, a truncated one and a CMYK one", "[io]") {
    TempFolder folder;
    const std::string png = folder / "picture.jpg";  // a PNG named .jpg
    ddt::writeImage(folder / "picture.png", ddt::test::photoCrop());
    fs::copy_file(folder / "picture.png", png);
    CHECK_THAT(ddt::test::userErrorOf([&] { JpegDecoder decoder(png, "picture.jpg"); }),
               Catch::StartsWith("picture.jpg: not a readable JPEG image ("));

    const std::string whole = folder / "whole.jpg", cut = folder / "cut.jpg";
    writeJpeg(whole, 300, 200, 3, photoCodes(3, 300, 200));
    fs::copy_file(whole, cut);
    fs::resize_file(cut, fs::file_size(whole) / 2);
    JpegDecoder truncated(cut, "cut.jpg");
    std::vector<uint8_t> codes(300 * 200 * 3);
    CHECK_THAT(ddt::test::userErrorOf([&] { truncated.decode(codes.data()); }),
               Catch::StartsWith("cut.jpg: truncated or corrupt image ("));
    JpegDecoder checked(cut, "cut.jpg");
    CHECK_THAT(ddt::test::userErrorOf([&] { checked.check(); }), Catch::StartsWith("cut.jpg: truncated or corrupt image ("));
    // Row by row the first rows come, then the same refusal.
    JpegDecoder rows(cut, "cut.jpg");
    rows.decodeRows(8, codes.data());
    CHECK_THAT(ddt::test::userErrorOf([&] { rows.decodeRows(192, codes.data()); }),
               Catch::StartsWith("cut.jpg: truncated or corrupt image ("));
    // A progressive file is read whole when stored again: refused there.
    const std::string progressive = folder / "progressive.jpg", cut_progressive = folder / "cut-progressive.jpg";
    writeJpeg(progressive, 300, 200, 3, photoCodes(3, 300, 200), [](OIIO::ImageSpec& s) { s.attribute("jpeg:progressive", 1); });
    fs::copy_file(progressive, cut_progressive);
    fs::resize_file(cut_progressive, fs::file_size(progressive) / 2);
    JpegDecoder scans(cut_progressive, "cut-progressive.jpg");
    CHECK_THAT(ddt::test::userErrorOf([&] { scans.sequential(); }),
               Catch::StartsWith("cut-progressive.jpg: truncated or corrupt image ("));

    const std::string cmyk = folder / "cmyk.jpg";
    writeByLibjpeg(cmyk, 16, 8, JCS_CMYK);
    const JpegDecoder four(cmyk, cmyk);
    CHECK(four.width() == 16);
    CHECK_FALSE(four.decodable());
}
