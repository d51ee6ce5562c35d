// Image quality metrics of the paper's Table 3 (Sec. 6): how close a reconstruction is to
// the original. Every metric compares 8-bit values, as the images would be stored.
//
// Definitions (x: original, y: reconstruction; n: number of values summed):
// - 8-bit values: round(clamp(v, 0, 1) · 255) of each colour channel (grey, or R, G, B);
//   an alpha channel is not compared.
// - luma: Y = 0.299 R + 0.587 G + 0.114 B of the 8-bit values, unrounded (grey: the value).
// - MSE: Σ (x − y)² / n over every colour channel of every pixel.
// - PSNR (dB): 10 · log10(255² / MSE); +∞ for identical images.
// - SNR (dB): 10 · log10(Σ x² / Σ (x − y)²) over every colour channel: signal energy over
//   error energy (not variance); +∞ for identical images.
// - correlation: Pearson's coefficient of the luma of all pixels,
//   Σ (x − x̄)(y − ȳ) / √(Σ (x − x̄)² · Σ (y − ȳ)²); NaN when either image is flat.
// - cross-correlation: the zero-mean normalised cross-correlation of all colour channels
//   together, each channel centred on its own mean:
//   Σ_c Σ (x_c − x̄_c)(y_c − ȳ_c) / √(Σ_c Σ (x_c − x̄_c)² · Σ_c Σ (y_c − ȳ_c)²).
//   Unlike correlation it also sees chroma errors; for grey images the two are equal.
//   (The paper does not define its "cross cor."; this is our choice.)
// - UIQI (Wang & Bovik 2002) on luma: Q = 4 σxy μx μy / ((σx² + σy²)(μx² + μy²)) in every
//   8×8 window lying fully inside the image (step 1, no padding), averaged. Where both
//   windows are flat (σx² + σy² = 0) Q = 2 μx μy / (μx² + μy²), and 1 where both are also
//   black, as in the authors' reference code. Flatness is tested exactly (integer sums).
// - SSIM (Wang et al. 2004) on luma: ((2 μx μy + C1)(2 σxy + C2)) /
//   ((μx² + μy² + C1)(σx² + σy² + C2)), C1 = (0.01 L)², C2 = (0.03 L)², L = 255, with the
//   means and (biased) variances weighted by the 11×11 Gaussian window of σ = 1.5 (weights
//   normalised to sum 1), averaged over the window positions lying fully inside the image.
//   No padding and no automatic downsampling.
//
// UIQI needs images of at least 8×8 pixels, SSIM at least 11×11.
#pragma once

#include <cstdint>
#include <vector>

#include "image.h"

namespace ddt {

// The colour channels of an image as 8-bit values, interleaved.
struct ByteImage {
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t channels = 0;  // 1 grey, 3 RGB
    std::vector<uint8_t> values;
};

// The 8-bit colour values of `image` (alpha dropped; colour as stored, i.e. premultiplied).
ByteImage toBytes(const Image& image);

// Both images must have the same size and channel count.
double meanSquaredError(const ByteImage& original, const ByteImage& other);
double peakSignalToNoiseRatio(const ByteImage& original, const ByteImage& other);
double signalToNoiseRatio(const ByteImage& original, const ByteImage& other);
double lumaCorrelation(const ByteImage& original, const ByteImage& other);
double crossCorrelation(const ByteImage& original, const ByteImage& other);
double universalQualityIndex(const ByteImage& original, const ByteImage& other);
double structuralSimilarity(const ByteImage& original, const ByteImage& other);

struct QualityScores {
    double mse = 0.0;
    double psnr = 0.0;               // dB
    double snr = 0.0;                // dB
    double correlation = 0.0;        // fraction; Table 3 shows percent
    double cross_correlation = 0.0;  // fraction; Table 3 shows percent
    double uiqi = 0.0;
    double ssim = 0.0;
};

QualityScores compareImages(const ByteImage& original, const ByteImage& other);

}  // namespace ddt
