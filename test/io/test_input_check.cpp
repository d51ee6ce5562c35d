// The checks made before a file reaches its decoder (core/input_check.h), on tiny hand-made
// files that carry the damage the fuzzer found each one for, and through the executable.
#include <catch2/catch.hpp>

#include <fstream>

#include "input_check.h"
#include "png_bytes.h"
#include "run_ddtup.h"
#include "temp_folder.h"

namespace {

std::string le16(uint32_t value) { return {char(value & 0xFF), char(value >> 8)}; }

void writeBytes(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

// A GIF of one 1×1 frame on a `width` × `height` logical screen, two colours.
std::string gifWithScreen(uint32_t width, uint32_t height) {
    const std::string screen =
        le16(width) + le16(height) + std::string("\x80\0\0", 3) + std::string("\0\0\0\xFF\xFF\xFF", 6);
    const std::string frame = std::string("\x2C\0\0\0\0", 5) + le16(1) + le16(1) + std::string(1, '\0');
    // LZW, minimum code size 2: clear (4), index 0, end (5), in 3-bit codes.
    const std::string data("\x02\x02\x44\x01\x00", 5);
    return "GIF89a" + screen + frame + data + "\x3B";
}

// A 2×2 colour-mapped Targa (type 1, or 9 with RLE) with a map of `entries` 24-bit colours.
std::string colourMappedTarga(bool rle, uint32_t entries, const std::string& pixels) {
    std::string header = std::string{'\0', '\1', char(rle ? 9 : 1)} + le16(0) + le16(entries) + char(24) + le16(0) +
                         le16(0) + le16(2) + le16(2) + char(8) + char(0x20);
    return header + std::string(3 * entries, '\x7F') + pixels;
}

// A 2×2 BMP (BITMAPINFOHEADER) of `bits` per pixel and `compression`, with `data` after it.
std::string bmp(uint32_t bits, uint32_t compression, const std::string& data) {
    auto le32 = [](uint32_t v) { return le16(v & 0xFFFF) + le16(v >> 16); };
    const std::string info = le32(40) + le32(2) + le32(2) + le16(1) + le16(bits) + le32(compression) +
                             le32(uint32_t(data.size())) + le32(2835) + le32(2835) + le32(0) + le32(0);
    return "BM" + le32(uint32_t(54 + data.size())) + le32(0) + le32(54) + info + data;
}

}  // namespace

TEST_CASE("input check: a PNG whose chunks are not all whole up to IEND is refused") {
    TempFolder folder;
    const std::string png = ddt::test::pngClaiming(4, 4);
    writeBytes(folder / "whole.png", png);
    CHECK(ddt::checkBeforeDecoding(folder / "whole.png", "png").empty());

    // IHDR 8-33, IDAT 33-53, IEND 53-65.
    writeBytes(folder / "cut.png", png.substr(0, 45));
    CHECK(ddt::checkBeforeDecoding(folder / "cut.png", "png") == "truncated PNG (it ends inside its IDAT chunk)");
    writeBytes(folder / "no-end.png", png.substr(0, 53));
    CHECK(ddt::checkBeforeDecoding(folder / "no-end.png", "png") == "truncated PNG (it ends before its IEND chunk)");
}

// OIIO 2.4 sized its canvas in an int: 65535 × 65535 × 4 overflowed into a negative size,
// which threw out of the reader (ddtup said "internal error", exit code 4).
TEST_CASE("input check: a GIF's logical screen over 2^28 pixels is refused before OIIO opens it") {
    TempFolder folder;
    writeBytes(folder / "small.gif", gifWithScreen(8, 8));
    CHECK(ddt::checkBeforeDecoding(folder / "small.gif", "gif").empty());
    writeBytes(folder / "huge.gif", gifWithScreen(65535, 65535));
    CHECK_THAT(ddt::checkBeforeDecoding(folder / "huge.gif", "gif"), Catch::StartsWith("image is 65535×65535 pixels"));

    const Run run = runDdtup({folder / "huge.gif", folder / "out.png"});
    requireOneLineError(run, 1, "huge.gif", "65535×65535");
}

// OIIO 2.4 looked colour indices up without a bounds check: index 200 of a 4-colour map read
// past the map (a crash, under AddressSanitizer a SEGV report).
TEST_CASE("input check: a colour-mapped Targa with an index beyond its map is refused") {
    TempFolder folder;
    writeBytes(folder / "good.tga", colourMappedTarga(false, 4, std::string("\0\1\2\3", 4)));
    CHECK(ddt::checkBeforeDecoding(folder / "good.tga", "targa").empty());
    writeBytes(folder / "raw.tga", colourMappedTarga(false, 4, std::string("\0\1\xC8\3", 4)));
    CHECK(ddt::checkBeforeDecoding(folder / "raw.tga", "targa") ==
          "colour index 200 lies outside the colour map of 4 entries");
    // RLE: a raw packet of two, then a run of two of index 4.
    writeBytes(folder / "good-rle.tga", colourMappedTarga(true, 5, std::string("\x01\0\1\x81\4", 5)));
    CHECK(ddt::checkBeforeDecoding(folder / "good-rle.tga", "targa").empty());
    writeBytes(folder / "rle.tga", colourMappedTarga(true, 4, std::string("\x01\0\1\x81\4", 5)));
    CHECK(ddt::checkBeforeDecoding(folder / "rle.tga", "targa") ==
          "colour index 4 lies outside the colour map of 4 entries");

    const Run run = runDdtup({folder / "raw.tga", folder / "out.png"});
    requireOneLineError(run, 1, "raw.tga", "colour index 200");
}

// OIIO 2.4 reads no colour table at 16 bits per pixel but looked RLE-coded pixels up in it:
// an empty table, read at index -1 (a crash, under AddressSanitizer a SEGV report).
TEST_CASE("input check: a BMP run-length coded at a depth RLE does not allow is refused") {
    TempFolder folder;
    const std::string rle("\x02\x11\0\0\x02\x11\0\1", 8);  // two rows of 2 pixels, end of bitmap
    writeBytes(folder / "rle4.bmp", bmp(4, 2, rle));
    CHECK(ddt::checkBeforeDecoding(folder / "rle4.bmp", "bmp").empty());
    writeBytes(folder / "deep.bmp", bmp(16, 2, rle));
    CHECK(ddt::checkBeforeDecoding(folder / "deep.bmp", "bmp") ==
          "BMP compressed with RLE4 at 16 bits per pixel (RLE8 needs 8, RLE4 needs 4)");

    const Run run = runDdtup({folder / "deep.bmp", folder / "out.png"});
    requireOneLineError(run, 1, "deep.bmp", "RLE4 at 16 bits");
}
