// PNG files written byte by byte, for what no encoder writes: headers claiming 100000×100000
// or 0×0 pixels, and damaged chunks.
#pragma once

#include <cstdint>
#include <string>

namespace ddt::test {

// The chunk `type` with `data`, its length and its CRC, as the PNG specification lays it out.
std::string pngChunk(const std::string& type, const std::string& data);

// A whole 8-bit RGB PNG whose header says width × height but whose image data is a few bytes:
// enough to be opened, never enough to be decoded.
std::string pngClaiming(uint32_t width, uint32_t height);

// Byte offset of the first byte of the data of the first chunk of `type` in `png`, or npos.
size_t pngChunkData(const std::string& png, const std::string& type);

// A small ICC profile of `colour_space` ("RGB ", "GRAY"), whole and valid (png_bytes.cpp).
std::string iccProfile(const char* colour_space);

// Recomputes the CRC of the chunk whose data starts at `data_offset` (after editing it).
void fixPngChunkCrc(std::string& png, size_t data_offset);

}  // namespace ddt::test
