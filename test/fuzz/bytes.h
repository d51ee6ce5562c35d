// Reading and writing integers in file bytes, and the checksums and zlib streams that the
// damage must keep valid (damage that only breaks a checksum tests only the checksum).
// Reads past the end give 0 and writes past the end are dropped: damaged files are short.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace fuzz {

uint32_t getBE(const std::string& bytes, size_t at, int size);
uint32_t getLE(const std::string& bytes, size_t at, int size);
void putBE(std::string& bytes, size_t at, int size, uint64_t value);
void putLE(std::string& bytes, size_t at, int size, uint64_t value);
uint64_t getLE64(const std::string& bytes, size_t at);

// `value` as `size` bytes, to build files with.
std::string be(int size, uint64_t value);
std::string le(int size, uint64_t value);

// zlib's CRC-32 (PNG chunks).
uint32_t crc32Of(const std::string& bytes);

// A zlib stream of `data` (PNG's IDAT, iCCP), and back; nullopt when `stream` is not one.
std::string zlibCompress(const std::string& data);
std::optional<std::string> zlibDecompress(const std::string& stream);

}  // namespace fuzz
