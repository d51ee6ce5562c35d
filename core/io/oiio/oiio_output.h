// An image file written through OpenImageIO's writer of its format (codec_module.h's CodecOutput).
#pragma once

#include <memory>

#include "codec_module.h"

namespace ddt {

std::unique_ptr<CodecOutput> openOiioOutput(const OutputRequest& request, OutputLayout& layout);

// Whether OpenImageIO's writer of `format` keeps an alpha channel.
bool oiioWritesAlpha(const ImageFormat& format);

}  // namespace ddt
