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
// Sobel operator, divided by 8 so that g is per pixel), its structure tensor J = g gᵀ smoothed
// by a Gaussian of σ = 1 pixel (radius 3), T = trace J (the smoothed |g|²) and the coherence
// C = ((λ₁ − λ₂) / (λ₁ + λ₂))² of J's eigenvalues (1 along a straight edge, near 0 in grain),
//     w(p) = kWeightFlat + (kWeightEdge − kWeightFlat) · clamp((log10 T − kLogFlat) / (kLogEdge − kLogFlat), 0, 1)
//                                                   · (kGrainShare + (1 − kGrainShare) · C).
// The coherence term is why grain of high contrast (leaves, gravel, raindrops) leans on the
// convolution while edges keep the surface: the mesh's facets and the consistent step's
// sharpening help along a line and show as creases across grain. The grain's share follows
// the assumed downscale (grainShareFor).
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
#include <memory>
#include <vector>

#include "assumed_kernel.h"
#include "image.h"
#include "render.h"

namespace ddt {

constexpr float kWeightFlat = 0.1f;
constexpr float kWeightEdge = 0.9f;
constexpr float kLogFlat = -4.25f;
constexpr float kLogEdge = -1.5f;
// The share of the contrast's weight that grain without orientation (C = 0) keeps.
constexpr float kGrainShare = 0.4f;

// The grain's share for a surface reconstructed under `kernel`: 1 (no coherence term) under
// the footprint, which the default assumes of JPEG files, kGrainShare under any other. Chosen
// on half a of the held-out photographs (bench/README.md, "Grain"): the coherence term lifts
// the rows of Lanczos3, bicubic and bilinear shrinks under `mixed`, and costs the JPEG rows,
// whose surface under the footprint fits their grain.
float grainShareFor(AssumedKernel kernel);

// The input pixels a sample of the fallback reaches beyond the one it lies in.
constexpr uint32_t kFallbackReach = 5;

// The surface's weight w(p) at every pixel of `image` (row-major), with `grain_share` in place
// of kGrainShare.
std::vector<float> surfaceWeights(const Image& image, float grain_share);

struct LanczosTaps;

// Blends rendered rows of a window towards the Lanczos3 convolution of the input the window's
// mesh was made of (its crop at window.crop_x, crop_y).
class ConvolutionFallback {
public:
    // `input` is the crop the surface was made of; it is copied, so the caller may drop it.
    ConvolutionFallback(const Image& input, float grain_share);
    ~ConvolutionFallback();
    ConvolutionFallback(ConvolutionFallback&&) noexcept;
    ConvolutionFallback& operator=(ConvolutionFallback&&) noexcept;

    // `rows` as MeshRenderer::renderWindow writes them for `window`; bands of one window may
    // be blended on several threads at once.
    void blend(const RenderWindow& window, float* rows, size_t row_stride = 0) const;
    // The bytes of its copy of the input and its weights.
    size_t bytes() const { return input_.pixels.capacity() * sizeof(float) + weights_.capacity() * sizeof(float); }

private:
    struct ColumnCache;
    std::shared_ptr<const std::vector<LanczosTaps>> columnsOf(const RenderWindow& window) const;
    template <uint32_t c>
    void blendWith(const RenderWindow& window, float* rows, size_t row_stride) const;

    Image input_;
    std::vector<float> weights_;
    std::unique_ptr<ColumnCache> columns_;
};

}  // namespace ddt
