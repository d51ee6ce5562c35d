// The float value of each code of an 8- or 16-bit image file: code / (2^bits − 1), computed
// as OpenImageIO 2.4 converts (a product with the float reciprocal), so that unpacked codes
// equal what a float read gives, bit for bit.
#pragma once

#include <cstdint>
#include <vector>

namespace ddt {

// 256 or 65536 values, indexed by code; `bits` is 8 or 16.
std::vector<float> valuesOfCodes(uint32_t bits);

}  // namespace ddt
