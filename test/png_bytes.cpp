#include "png_bytes.h"

#include <random>

namespace ddt::test {

namespace {

// CRC-32 as PNG defines it (ISO 3309, polynomial 0xEDB88320, reflected), bit by bit.
uint32_t crc32(const std::string& bytes) {
    uint32_t crc = 0xFFFFFFFFu;
    for (unsigned char byte : bytes) {
        crc ^= byte;
        for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return crc ^ 0xFFFFFFFFu;
}

std::string bigEndian(uint32_t value) {
    return {char(value >> 24), char(value >> 16), char(value >> 8), char(value)};
}

uint32_t readBigEndian(const std::string& bytes, size_t at) {
    uint32_t value = 0;
    for (size_t i = 0; i < 4; ++i) value = (value << 8) | uint8_t(bytes[at + i]);
    return value;
}

const char kSignature[] = "\x89PNG\r\n\x1a\n";

}  // namespace

std::string pngChunk(const std::string& type, const std::string& data) {
    return bigEndian(uint32_t(data.size())) + type + data + bigEndian(crc32(type + data));
}

std::string pngClaiming(uint32_t width, uint32_t height) {
    // Bit depth 8, colour type 2 (RGB), deflate, adaptive filtering, no interlace.
    const std::string header = bigEndian(width) + bigEndian(height) + std::string("\x08\x02\x00\x00\x00", 5);
    // A zlib stream holding nothing: header 78 9C, an empty final fixed block, Adler-32 of "".
    const std::string empty_zlib("\x78\x9c\x03\x00\x00\x00\x00\x01", 8);
    return std::string(kSignature, 8) + pngChunk("IHDR", header) + pngChunk("IDAT", empty_zlib) + pngChunk("IEND", "");
}

size_t pngChunkData(const std::string& png, const std::string& type) {
    for (size_t at = 8; at + 12 <= png.size();) {
        const uint32_t length = readBigEndian(png, at);
        if (png.compare(at + 4, 4, type) == 0) return at + 8;
        at += 12 + size_t(length);
    }
    return std::string::npos;
}

void fixPngChunkCrc(std::string& png, size_t data_offset) {
    const size_t start = data_offset - 8;
    const uint32_t length = readBigEndian(png, start);
    const std::string crc = bigEndian(crc32(png.substr(start + 4, 4 + size_t(length))));
    png.replace(data_offset + length, 4, crc);
}

// A small ICC profile: the 128-byte header (its size, version 2.1, a display profile of
// `colour_space`, XYZ connection space, the signature, D50) and one private tag of 256
// pseudo-random bytes. Those keep the compressed profile over 91 bytes: libpng 1.6.39's reader
// ignores a shorter iCCP chunk ("too short": it reads 81 bytes, then wants 11 more).
std::string iccProfile(const char* colour_space) {
    const size_t size = 128 + 4 + 12 + 256;
    std::string profile(size, '\0');
    auto put = [&](size_t at, uint32_t value) {
        for (int i = 0; i < 4; ++i) profile[at + i] = char(value >> (24 - 8 * i));
    };
    put(0, uint32_t(size));
    put(8, 0x02100000);
    profile.replace(12, 4, "mntr");
    profile.replace(16, 4, colour_space);
    profile.replace(20, 4, "XYZ ");
    profile.replace(36, 4, "acsp");
    put(68, 0x0000F6D6);
    put(72, 0x00010000);
    put(76, 0x0000D32D);
    put(128, 1);  // one tag: its signature, offset and size
    profile.replace(132, 4, "ddtz");
    put(136, 144);
    put(140, 256);
    std::mt19937 rng(3);
    for (size_t i = 144; i < size; ++i) profile[i] = char(rng());
    return profile;
}

}  // namespace ddt::test
