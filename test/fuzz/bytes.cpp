#include "bytes.h"

#include <zlib.h>

namespace fuzz {

uint32_t getBE(const std::string& bytes, size_t at, int size) {
    uint32_t value = 0;
    for (int i = 0; i < size; ++i) value = (value << 8) | (at + i < bytes.size() ? uint8_t(bytes[at + i]) : 0);
    return value;
}

uint32_t getLE(const std::string& bytes, size_t at, int size) {
    uint32_t value = 0;
    for (int i = size - 1; i >= 0; --i) value = (value << 8) | (at + i < bytes.size() ? uint8_t(bytes[at + i]) : 0);
    return value;
}

void putBE(std::string& bytes, size_t at, int size, uint64_t value) {
    for (int i = size - 1; i >= 0; --i, value >>= 8)
        if (at + i < bytes.size()) bytes[at + i] = char(value & 0xFF);
}

void putLE(std::string& bytes, size_t at, int size, uint64_t value) {
    for (int i = 0; i < size; ++i, value >>= 8)
        if (at + i < bytes.size()) bytes[at + i] = char(value & 0xFF);
}

uint64_t getLE64(const std::string& bytes, size_t at) {
    return uint64_t(getLE(bytes, at, 4)) | uint64_t(getLE(bytes, at + 4, 4)) << 32;
}

std::string be(int size, uint64_t value) {
    std::string out(size_t(size), '\0');
    putBE(out, 0, size, value);
    return out;
}

std::string le(int size, uint64_t value) {
    std::string out(size_t(size), '\0');
    putLE(out, 0, size, value);
    return out;
}

uint32_t crc32Of(const std::string& bytes) {
    return uint32_t(::crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), uInt(bytes.size())));
}

std::string zlibCompress(const std::string& data) {
    uLongf size = compressBound(uLong(data.size()));
    std::string out(size, '\0');
    compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(data.data()),
              uLong(data.size()), 6);
    out.resize(size);
    return out;
}

std::optional<std::string> zlibDecompress(const std::string& stream) {
    z_stream z{};
    if (inflateInit(&z) != Z_OK) return std::nullopt;
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(stream.data()));
    z.avail_in = uInt(stream.size());
    std::string out;
    char buffer[16384];
    int status = Z_OK;
    while (status == Z_OK) {
        z.next_out = reinterpret_cast<Bytef*>(buffer);
        z.avail_out = sizeof buffer;
        status = inflate(&z, Z_NO_FLUSH);
        out.append(buffer, sizeof buffer - z.avail_out);
    }
    inflateEnd(&z);
    if (status != Z_STREAM_END) return std::nullopt;
    return out;
}

}  // namespace fuzz
