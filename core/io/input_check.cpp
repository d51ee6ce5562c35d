#include "input_check.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "image.h"

namespace ddt {

namespace {

// The file's bytes, read where asked; short at the end of the file.
class FileBytes {
public:
    explicit FileBytes(const std::string& path) : in_(path, std::ios::binary) {
        std::error_code error;
        size_ = std::filesystem::file_size(path, error);
        if (error) size_ = 0;
    }
    uint64_t size() const { return size_; }
    std::string read(uint64_t at, size_t count) {
        if (at >= size_) return "";
        std::string bytes(std::min<uint64_t>(count, size_ - at), '\0');
        in_.clear();
        in_.seekg(std::streamoff(at));
        in_.read(bytes.data(), std::streamsize(bytes.size()));
        bytes.resize(size_t(in_.gcount()));
        return bytes;
    }

private:
    std::ifstream in_;
    uint64_t size_ = 0;
};

uint32_t bigEndian32(const std::string& bytes, size_t at) {
    uint32_t value = 0;
    for (size_t i = 0; i < 4; ++i) value = value << 8 | uint8_t(bytes[at + i]);
    return value;
}

uint32_t littleEndian16(const std::string& bytes, size_t at) {
    return uint8_t(bytes[at]) | uint32_t(uint8_t(bytes[at + 1])) << 8;
}

uint32_t littleEndian32(const std::string& bytes, size_t at) {
    return littleEndian16(bytes, at) | littleEndian16(bytes, at + 2) << 16;
}

// PNG: OIIO's read callback, at the end of the file, hands libpng an error message in a
// temporary string and libpng's longjmp skips its destructor: every truncated PNG leaked
// it (LeakSanitizer). libpng reads chunk by chunk, so a file whose chunks are all whole up
// to IEND is never read past its end.
std::string checkPng(FileBytes& file) {
    for (uint64_t at = 8;;) {
        const std::string header = file.read(at, 8);
        if (header.size() < 8) return "truncated PNG (it ends before its IEND chunk)";
        const std::string type = header.substr(4, 4);
        const bool named = std::all_of(type.begin(), type.end(), [](char c) { return std::isalpha(uint8_t(c)) != 0; });
        if (at + 12 + bigEndian32(header, 0) > file.size())
            return "truncated PNG (it ends inside its " + (named ? type : std::string("damaged")) + " chunk)";
        if (type == "IEND") return "";
        at += 12 + uint64_t(bigEndian32(header, 0));
    }
}

// GIF: OIIO sizes its canvas as width × height × 4 in an int, which overflows for a large
// logical screen (to a negative size that throws, or a small one that the frame is then
// drawn past), while the file is opened, before ddtup can look at the size.
std::string checkGif(FileBytes& file) {
    const std::string screen = file.read(6, 4);
    if (screen.size() < 4) return "";  // giflib reports the truncation
    const uint64_t width = littleEndian16(screen, 0), height = littleEndian16(screen, 2);
    if (width * height <= kMaxInputPixels) return "";
    return "image is " + std::to_string(width) + "×" + std::to_string(height) + " pixels; ddtup reads at most " +
           std::to_string(kMaxInputPixels) + " pixels (16384×16384)";
}

// Targa: OIIO looks colour-mapped pixels up in the colour map without a bounds check (and
// adds the map's first index instead of subtracting it), so an index beyond the map reads
// past it (a crash). Every index is checked, through the run-length packets if any.
std::string checkTarga(FileBytes& file) {
    const std::string header = file.read(0, 18);
    if (header.size() < 18) return "";
    const int type = uint8_t(header[2]);
    if (type != 1 && type != 9) return "";  // not colour-mapped
    const uint32_t first = littleEndian16(header, 3), length = littleEndian16(header, 5);
    const int entry_bits = uint8_t(header[7]), index_bits = uint8_t(header[16]);
    const size_t index_bytes = index_bits == 15 ? 2 : size_t(index_bits) / 8;
    if (index_bytes == 0 || index_bytes > 4) return "";  // OIIO refuses these depths
    const uint64_t pixels = uint64_t(littleEndian16(header, 12)) * littleEndian16(header, 14);
    const uint64_t map_bytes = uint64_t(length) * (entry_bits == 15 ? 2 : uint64_t(entry_bits) / 8);
    const std::string data = file.read(18 + uint8_t(header[0]) + map_bytes,
                                       size_t(std::min<uint64_t>(file.size(), pixels * (index_bytes + 1))));
    auto indexAt = [&](size_t at) {
        uint32_t index = 0;
        for (size_t i = 0; i < index_bytes; ++i) index |= uint32_t(uint8_t(data[at + i])) << (8 * i);
        return index;
    };
    size_t at = 0;
    for (uint64_t done = 0; done < pixels && at < data.size();) {
        // One index, or (RLE) a packet: a run of one index, or that many indices.
        uint64_t count = 1, indices = 1;
        if (type == 9) {
            const uint8_t packet = uint8_t(data[at++]);
            count = (packet & 0x7F) + 1;
            indices = packet & 0x80 ? 1 : count;
        }
        for (uint64_t i = 0; i < indices && at + index_bytes <= data.size(); ++i, at += index_bytes)
            if (uint64_t(first) + indexAt(at) >= length)
                return "colour index " + std::to_string(indexAt(at)) + " lies outside the colour map of " +
                       std::to_string(length) + " entries";
        done += count;
    }
    return "";
}

// BMP: OIIO reads the colour table only for 1, 4 and 8 bits per pixel, but expands run-length
// compressed pixels through it whatever the depth, so RLE at 16, 24 or 32 bits per pixel
// indexed an empty table (a crash). The format allows RLE8 only at 8 bits, RLE4 only at 4.
std::string checkBmp(FileBytes& file) {
    const std::string header = file.read(14, 20);
    if (header.size() < 20 || littleEndian32(header, 0) == 12) return "";  // OS/2's header: no compression
    const uint32_t bits = littleEndian16(header, 14), compression = littleEndian32(header, 16);
    if ((compression == 1 && bits != 8) || (compression == 2 && bits != 4))
        return std::string("BMP compressed with ") + (compression == 1 ? "RLE8" : "RLE4") + " at " +
               std::to_string(bits) + " bits per pixel (RLE8 needs 8, RLE4 needs 4)";
    return "";
}

}  // namespace

std::string checkBeforeDecoding(const std::string& path, const std::string& format_name) {
    FileBytes file(path);
    if (format_name == "png") return checkPng(file);
    if (format_name == "gif") return checkGif(file);
    if (format_name == "bmp") return checkBmp(file);
    if (format_name == "targa") return checkTarga(file);
    return "";
}

}  // namespace ddt
