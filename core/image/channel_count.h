// Dispatch on an image's channel count, so that per-channel loops in hot code have a constant
// trip count the compiler unrolls (and their small arrays stay in registers).
#pragma once

#include <cstdint>
#include <type_traits>

namespace ddt {

// Calls f(std::integral_constant<uint32_t, channels>) for channels 1 to 4.
template <typename F>
void withChannelCount(uint32_t channels, F f) {
    switch (channels) {
    case 1: f(std::integral_constant<uint32_t, 1>()); break;
    case 2: f(std::integral_constant<uint32_t, 2>()); break;
    case 3: f(std::integral_constant<uint32_t, 3>()); break;
    default: f(std::integral_constant<uint32_t, 4>()); break;
    }
}

}  // namespace ddt
