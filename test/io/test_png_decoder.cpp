// PngDecoder against OpenImageIO's PNG reader (libpng): every sample equal for each colour type,
// depth and transparency a PNG file can have (and readPngHeader's layout and attributes); its
// EXIF and ICC chunks; bad files in one line.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>
#include <spng.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "header_checks.h"
#include "image_file.h"
#include "png_decoder.h"
#include "png_header.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

using ddt::PngDecoder;
namespace fs = std::filesystem;

// What a test file holds besides its samples.
struct Extras {
    bool transparency = false;  // a tRNS chunk (for grey and RGB: one colour; for palettes: alphas)
    bool interlaced = false;
    std::vector<uint8_t> exif, icc;
};

// The bytes of a width × height image of `colour_type` and `depth` as PNG stores them (rows
// packed, 16-bit samples big-endian), random but for a repeated first pixel, so that a tRNS
// colour (the first pixel's) occurs.
std::vector<uint8_t> storedSamples(uint32_t width, uint32_t height, int colour_type, int depth, std::mt19937& rng) {
    const int samples = colour_type == SPNG_COLOR_TYPE_TRUECOLOR ? 3
                        : colour_type == SPNG_COLOR_TYPE_GRAYSCALE_ALPHA ? 2
                        : colour_type == SPNG_COLOR_TYPE_TRUECOLOR_ALPHA ? 4
                                                                          : 1;
    const size_t row_bytes = (size_t(width) * samples * depth + 7) / 8;
    std::vector<uint8_t> bytes(row_bytes * height);
    for (uint8_t& byte : bytes) byte = uint8_t(rng());
    if (colour_type == SPNG_COLOR_TYPE_INDEXED && depth == 8)
        for (uint8_t& byte : bytes) byte %= 16;  // the palette's 16 entries
    for (uint32_t y = 0; y < height; ++y)  // every row starts as the first: the tRNS colour
        std::copy_n(bytes.begin(), std::min<size_t>(row_bytes, 2 * samples), bytes.begin() + y * row_bytes);
    return bytes;
}

// Writes a PNG file with libspng's encoder.
void writePng(const std::string& path, uint32_t width, uint32_t height, int colour_type, int depth,
              const std::vector<uint8_t>& stored, const Extras& extras) {
    spng_ctx* context = spng_ctx_new(SPNG_CTX_ENCODER);
    std::FILE* file = std::fopen(path.c_str(), "wb");
    REQUIRE(file);
    REQUIRE(spng_set_png_file(context, file) == 0);
    spng_ihdr header{width, height, uint8_t(depth), uint8_t(colour_type), 0, 0, uint8_t(extras.interlaced ? 1 : 0)};
    REQUIRE(spng_set_ihdr(context, &header) == 0);
    if (colour_type == SPNG_COLOR_TYPE_INDEXED) {
        spng_plte palette{};
        palette.n_entries = 16;
        for (uint32_t i = 0; i < 16; ++i) palette.entries[i] = {uint8_t(16 * i), uint8_t(255 - 9 * i), uint8_t(i * i), 255};
        REQUIRE(spng_set_plte(context, &palette) == 0);
    }
    if (extras.transparency) {
        spng_trns transparency{};
        const int max = (1 << depth) - 1;
        auto sample = [&](int k) {  // the first pixel's k-th sample, as stored
            return depth == 16 ? uint16_t(stored[2 * k] << 8 | stored[2 * k + 1]) : uint16_t(stored[0] >> (8 - depth) & max);
        };
        if (colour_type == SPNG_COLOR_TYPE_GRAYSCALE) transparency.gray = sample(0);
        if (colour_type == SPNG_COLOR_TYPE_TRUECOLOR) {
            transparency.red = depth == 16 ? sample(0) : stored[0];
            transparency.green = depth == 16 ? sample(1) : stored[1];
            transparency.blue = depth == 16 ? sample(2) : stored[2];
        }
        if (colour_type == SPNG_COLOR_TYPE_INDEXED) {
            transparency.n_type3_entries = 16;
            for (uint32_t i = 0; i < 16; ++i) transparency.type3_alpha[i] = uint8_t(17 * i);
        }
        REQUIRE(spng_set_trns(context, &transparency) == 0);
    }
    if (!extras.exif.empty()) {
        spng_exif exif{extras.exif.size(), reinterpret_cast<char*>(const_cast<uint8_t*>(extras.exif.data()))};
        REQUIRE(spng_set_exif(context, &exif) == 0);
    }
    if (!extras.icc.empty()) {
        spng_iccp icc{};
        std::snprintf(icc.profile_name, sizeof(icc.profile_name), "test profile");
        icc.profile_len = extras.icc.size();
        icc.profile = reinterpret_cast<char*>(const_cast<uint8_t*>(extras.icc.data()));
        REQUIRE(spng_set_iccp(context, &icc) == 0);
    }
    const int error = spng_encode_image(context, stored.data(), stored.size(), SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE);
    INFO(spng_strerror(error));
    REQUIRE(error == 0);
    spng_ctx_free(context);
    std::fclose(file);
}

// OpenImageIO's samples of the file, as bytes of its own type, and its channel count and depth.
struct Read {
    std::vector<uint8_t> bytes;
    uint32_t channels = 0, bits = 0;
};

Read readByOpenImageIO(const std::string& path) {
    // Colour as stored under alpha, as ddtup's reader asks (OpenImageIO would premultiply it).
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto input = OIIO::ImageInput::open(path, &config);
    REQUIRE(input);
    const OIIO::ImageSpec& spec = input->spec();
    Read read{std::vector<uint8_t>(spec.image_bytes()), uint32_t(spec.nchannels), uint32_t(spec.format.size() * 8)};
    REQUIRE(input->read_image(0, 0, 0, spec.nchannels, spec.format, read.bytes.data()));
    return read;
}

Read readByDecoder(const std::string& path) {
    PngDecoder decoder(path, path);
    Read read{std::vector<uint8_t>(size_t(decoder.width()) * decoder.height() * decoder.channels() * decoder.sampleBits() / 8),
              decoder.channels(), decoder.sampleBits()};
    decoder.decode(read.bytes.data());
    return read;
}

// The samples by decodeRows in runs of 1, 2, 3 … rows, as a PackedImage asks for them.
Read readInRuns(const std::string& path) {
    PngDecoder decoder(path, path);
    const size_t row_bytes = size_t(decoder.width()) * decoder.channels() * decoder.sampleBits() / 8;
    Read read{std::vector<uint8_t>(row_bytes * decoder.height()), decoder.channels(), decoder.sampleBits()};
    for (uint32_t y = 0, run = 1; y < decoder.height(); y += run, ++run) {
        run = std::min(run, decoder.height() - y);
        decoder.decodeRows(run, read.bytes.data() + y * row_bytes);
    }
    return read;
}

}  // namespace

TEST_CASE("png decoder: every sample equals OpenImageIO's for each colour type, depth, transparency and interlacing",
          "[io]") {
    TempFolder folder;
    std::mt19937 rng(7);
    struct Case {
        int colour_type;
        std::vector<int> depths;
    };
    const Case cases[] = {{SPNG_COLOR_TYPE_GRAYSCALE, {1, 2, 4, 8, 16}},
                          {SPNG_COLOR_TYPE_TRUECOLOR, {8, 16}},
                          {SPNG_COLOR_TYPE_INDEXED, {4, 8}},
                          {SPNG_COLOR_TYPE_GRAYSCALE_ALPHA, {8, 16}},
                          {SPNG_COLOR_TYPE_TRUECOLOR_ALPHA, {8, 16}}};
    int files = 0;
    for (const Case& c : cases)
        for (int depth : c.depths)
            for (bool transparency : {false, true})
                for (bool interlaced : {false, true}) {
                    const bool has_alpha = c.colour_type == SPNG_COLOR_TYPE_GRAYSCALE_ALPHA ||
                                           c.colour_type == SPNG_COLOR_TYPE_TRUECOLOR_ALPHA;
                    if (transparency && has_alpha) continue;  // PNG allows no tRNS beside an alpha channel
                    INFO("colour type " << c.colour_type << ", depth " << depth << ", tRNS " << transparency
                                        << ", interlaced " << interlaced);
                    const std::string path = folder / (std::to_string(files++) + ".png");
                    const uint32_t width = 37, height = 23;  // odd: partial bytes at the ends of low-depth rows
                    writePng(path, width, height, c.colour_type, depth,
                             storedSamples(width, height, c.colour_type, depth, rng), {transparency, interlaced, {}, {}});
                    const Read ours = readByDecoder(path), theirs = readByOpenImageIO(path);
                    CHECK(ours.channels == theirs.channels);
                    CHECK(ours.bits == theirs.bits);
                    CHECK(ours.bytes == theirs.bytes);
                    CHECK(PngDecoder(path, path).interlaced() == interlaced);
                    if (!interlaced) CHECK(readInRuns(path).bytes == theirs.bytes);
                    // Read for tiles a row at a time only where the rows come in order.
                    CHECK(ddt::ImageReader(path).readPacked(true).bytes() == (interlaced ? ours.bytes.size() : 0));
                    // The header the reader takes instead of OpenImageIO's: its layout and attributes.
                    const std::optional<ddt::PngHeader> header = ddt::readPngHeader(path, path, ddt::test::decodeExifByOpenImageIO);
                    REQUIRE(header);
                    CHECK(header->channels == theirs.channels);
                    CHECK(header->bits == theirs.bits);
                    ddt::test::requireSameAttributes(header->attributes, ddt::test::attributesByOpenImageIO(path));
                }
    CHECK(files == 44);
}

TEST_CASE("png decoder: the eXIf and iCCP chunks come out as written", "[io]") {
    TempFolder folder;
    std::mt19937 rng(3);
    Extras extras;
    // A minimal little-endian TIFF header with no entries: what eXIf must start with.
    extras.exif = {'I', 'I', 42, 0, 8, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    extras.icc.resize(3000);
    for (size_t i = 0; i < extras.icc.size(); ++i) extras.icc[i] = uint8_t(i * 31 + i / 97);
    const std::string path = folder / "tagged.png";
    writePng(path, 8, 8, SPNG_COLOR_TYPE_TRUECOLOR, 8, storedSamples(8, 8, SPNG_COLOR_TYPE_TRUECOLOR, 8, rng), extras);
    const PngDecoder decoder(path, path);
    CHECK(decoder.exif() == extras.exif);
    CHECK(decoder.iccProfile() == extras.icc);

    const std::string plain = folder / "plain.png";
    writePng(plain, 8, 8, SPNG_COLOR_TYPE_GRAYSCALE, 8, storedSamples(8, 8, SPNG_COLOR_TYPE_GRAYSCALE, 8, rng), {});
    const PngDecoder untagged(plain, plain);
    CHECK(untagged.exif().empty());
    CHECK(untagged.iccProfile().empty());
}

TEST_CASE("png decoder: a file that is not a PNG and a truncated one", "[io]") {
    TempFolder folder;
    const std::string text = folder / "notes.png";
    {
        std::FILE* file = std::fopen(text.c_str(), "wb");
        std::fputs("not a picture at all, just words in a file\n", file);
        std::fclose(file);
    }
    CHECK_THAT(ddt::test::userErrorOf([&] { PngDecoder decoder(text, "notes.png"); }),
               Catch::StartsWith("notes.png: not a readable PNG image ("));

    std::mt19937 rng(5);
    const std::string whole = folder / "whole.png", cut = folder / "cut.png";
    writePng(whole, 200, 100, SPNG_COLOR_TYPE_TRUECOLOR, 8, storedSamples(200, 100, SPNG_COLOR_TYPE_TRUECOLOR, 8, rng), {});
    fs::copy_file(whole, cut);
    fs::resize_file(cut, fs::file_size(whole) / 2);
    PngDecoder truncated(cut, "cut.png");
    std::vector<uint8_t> samples(200 * 100 * 3);
    CHECK_THAT(ddt::test::userErrorOf([&] { truncated.decode(samples.data()); }),
               Catch::StartsWith("cut.png: truncated or corrupt image ("));
    // Row by row the first rows come, then the same refusal.
    PngDecoder rows(cut, "cut.png");
    rows.decodeRows(4, samples.data());
    CHECK_THAT(ddt::test::userErrorOf([&] { rows.decodeRows(96, samples.data()); }),
               Catch::StartsWith("cut.png: truncated or corrupt image ("));
}
