// Byte counts as the user reads them in messages.
#pragma once

#include <cstdint>
#include <string>

namespace ddt {

// "N MiB", rounded up, so that a need is never shown smaller than it is.
inline std::string mebibytes(uint64_t bytes) { return std::to_string((bytes + (1 << 20) - 1) >> 20) + " MiB"; }

}  // namespace ddt
