// Checks made before a file reaches its decoder, for damage that OpenImageIO 2.4's readers
// (and the libraries under them) do not catch and fail on badly: a crash, an overflow, a
// leak. Each was found by the fuzzer (test/fuzz, scripts/fuzz); input_check.cpp says which.
#pragma once

#include <string>

namespace ddt {

// "" when `path` may go to the decoder of `format_name` (OIIO's name, as image_formats.h
// tells it: "png", "gif", "targa", …), else the reason, to be reported as "PATH: reason".
std::string checkBeforeDecoding(const std::string& path, const std::string& format_name);

}  // namespace ddt
