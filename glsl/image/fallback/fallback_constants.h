// The convolution fallback's constants (core/image/convolution_fallback.h, which the host
// checks against), for the kernels of glsl/image/fallback/.
#ifndef DDTUP_FALLBACK_CONSTANTS_H
#define DDTUP_FALLBACK_CONSTANTS_H

#ifdef __cplusplus
#include <cstdint>
namespace ddt {
typedef uint32_t uint;
#define DDT_FLOAT constexpr float  // a float const is not a C++ constant expression
#else
#define DDT_FLOAT const float
#endif

// Lanczos3 under magnification: 3 input pixels each side of a sample, per axis.
const uint kFallbackTaps = 6;
// The Gaussian of σ = 1 that smooths the gradient energy reaches 3 pixels each side.
const int kFallbackGaussianRadius = 3;
// The surface's weight from flat to strong edges, over log10 of the smoothed energy.
DDT_FLOAT kFallbackWeightFlat = 0.1;
DDT_FLOAT kFallbackWeightEdge = 0.9;
DDT_FLOAT kFallbackLogFlat = -4.25;
DDT_FLOAT kFallbackLogEdge = -1.5;

#ifdef __cplusplus
}  // namespace ddt
#endif
#undef DDT_FLOAT
#endif
