// The rows of an image's codes, decoded as they are asked for, top to bottom: what lets a
// PackedImage (packed_image.h) hold only the rows its tiles reach instead of the whole input
// (40 MB of codes for a 13 MP photograph, most of its run's memory). The file readers make
// one where their decoder can go row by row and the rows are stored upright.
#pragma once

#include <cstdint>

namespace ddt {

class RowDecoder {
public:
    virtual ~RowDecoder() = default;
    // The next `count` rows into `codes`: count × width × channels codes of the image's type
    // (uint8_t or uint16_t), channels interleaved. Throws InputError ("NAME: …") for a
    // truncated or corrupt file.
    virtual void decodeRows(uint32_t count, void* codes) = 0;
};

}  // namespace ddt
