// An image file read through OpenImageIO's reader of its format (codec_module.h's CodecInput).
#pragma once

#include <memory>
#include <string>

#include "codec_module.h"

namespace ddt {

std::unique_ptr<CodecInput> openOiioInput(const std::string& file, const std::string& name, const ImageFormat& format);

}  // namespace ddt
