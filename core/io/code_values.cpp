#include "code_values.h"

#include <cstddef>

namespace ddt {

std::vector<float> valuesOfCodes(uint32_t bits) {
    const uint32_t largest = (1u << bits) - 1;
    const float scale = 1.0f / float(largest);
    std::vector<float> values(std::size_t(largest) + 1);
    for (uint32_t code = 0; code <= largest; ++code) values[code] = float(code) * scale;
    return values;
}

}  // namespace ddt
