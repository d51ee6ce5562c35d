// A pixel's channels as one SIMD value (the GCC/Clang vector extension): the reconstruction's
// hot loops do each step for all channels at once. Vector arithmetic is lane-wise IEEE single
// precision, so every channel gets exactly the value the scalar expression gives it.
// Pixels stay packed in memory (3 channels take 3 floats); a 3-channel vector has a 4th lane,
// loaded as 0 and never stored.
#pragma once

#include <cstdint>

namespace ddt {

template <uint32_t Lanes>
struct FloatVector {
    typedef float type __attribute__((vector_size(sizeof(float) * Lanes)));
};
template <>
struct FloatVector<1> {
    typedef float type;
};

template <uint32_t C>
using PixelVector = typename FloatVector<C == 3 ? 4 : C>::type;

template <uint32_t C>
PixelVector<C> loadPixel(const float* p) {
    if constexpr (C == 1) return p[0];
    else if constexpr (C == 2) return PixelVector<C>{p[0], p[1]};
    else if constexpr (C == 3) return PixelVector<C>{p[0], p[1], p[2], 0.0f};
    else return PixelVector<C>{p[0], p[1], p[2], p[3]};
}

template <uint32_t C>
void storePixel(float* p, PixelVector<C> v) {
    if constexpr (C == 1) p[0] = v;
    else
        for (uint32_t k = 0; k < C; ++k) p[k] = v[k];
}

}  // namespace ddt
