// Raw 8-bit interleaved pixels as a bench input, so that any image can be benchmarked without
// an image library: `vips rawsave in.png out.raw` or `convert in.png -depth 8 rgb:out.raw`
// write them; the size comes separately as W x H x C.
#pragma once

#include <cstdint>
#include <string>

#include "image.h"

namespace ddt {

struct RawSize {
    uint32_t width = 0, height = 0, channels = 0;
};

// "WxHxC" (C 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA); throws UserError otherwise.
RawSize parseRawSize(const std::string& text);

// Reads exactly width × height × channels bytes; alpha is premultiplied as in every Image.
Image readRawImage(const std::string& path, RawSize size);

}  // namespace ddt
