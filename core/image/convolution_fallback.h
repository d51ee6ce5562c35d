// The convolution fallback (`--fallback lanczos3`): where the input has little contrast, the
// mesh's surface gives way to a Lanczos3 convolution of the input.
//
// Why: on photographs the piecewise surface loses to Lanczos3 on smooth, defocused content
// and on fine grain (grass, raindrops), where the mesh's facets show as creases, and wins on
// strong edges. Blending the two by local contrast keeps both: on 20 held-out photographs,
// 8 × 8-block least-squares weights of the surface against Lanczos3 rise from about 0.1 in
// flat regions to 0.9 on strong edges, as a function of the input's local gradient energy.
//
// The surface's weight at input pixel p: with the gradient g of the colour channels' mean (a
// Sobel operator, divided by 8 so that g is per pixel) and T = |g|² smoothed by a Gaussian of
// σ = 1 pixel (radius 3),
//     w(p) = kWeightFlat + (kWeightEdge − kWeightFlat) · clamp((log10 T − kLogFlat) / (kLogEdge − kLogFlat), 0, 1).
// An output sample takes w bilinearly from its input position and becomes
//     w · surface + (1 − w) · Lanczos3(input),
// kept to [0, 1] for integer sample types and colour within alpha, as the surface is.
// The constants were chosen on one half of the held-out photographs (bench/README.md).
//
// Reach: a sample reads input pixels up to 3 (Lanczos3) and its weights up to 1 + 4 (the
// bilinear weight, Sobel and the Gaussian) away from its position, within a tile's overlap
// (core/image/tiling.h), so tiles render the same pixels as the whole image.
#pragma once

#include <cstddef>
#include <vector>

#include "image.h"
#include "render.h"

namespace ddt {

constexpr float kWeightFlat = 0.1f;
constexpr float kWeightEdge = 0.9f;
constexpr float kLogFlat = -4.25f;
constexpr float kLogEdge = -1.5f;

// The input pixels a sample of the fallback reaches beyond the one it lies in.
constexpr uint32_t kFallbackReach = 5;

// The surface's weight w(p) at every pixel of `image` (row-major).
std::vector<float> surfaceWeights(const Image& image);

// Blends rendered rows of a window towards the Lanczos3 convolution of the input the window's
// mesh was made of (its crop at window.crop_x, crop_y).
class ConvolutionFallback {
public:
    // `input` is the crop the surface was made of; it is copied, so the caller may drop it.
    explicit ConvolutionFallback(const Image& input);

    // `rows` as MeshRenderer::renderWindow writes them for `window`.
    void blend(const RenderWindow& window, float* rows, size_t row_stride = 0) const;

private:
    Image input_;
    std::vector<float> weights_;
};

}  // namespace ddt
