// The downscale filters the consistent reconstruction (core/image/reconstruct.h) can assume made its
// input (`--assume`). A user's small image came from a camera, a photo editor's resize or a
// web service's: the filter decides how much detail near the input's Nyquist frequency is
// there to keep, and a reconstruction that assumes a blurrier filter than the real one
// smooths detail that the input holds, one that assumes a sharper filter invents detail.
//
// Measured on 13 outside photographs (python3-skimage's data, centre crops of at most 512²)
// against Lanczos3, mean PSNR difference at ×2 / ×4 (bench/README.md, "Assumed filter"): the
// right filter moves a Lanczos3-made input from −0.51 / −0.46 dB to −0.05 / +0.00 and a
// bicubic-made one from −0.04 / −0.07 to +0.14 / +0.11.
#pragma once

#include <optional>
#include <string>

namespace ddt {

// The footprint's standard deviation as the factor grows, in input pixels (core/image/reconstruct.h).
constexpr double kFootprintSigma = 0.4;

enum class AssumedKernel {
    footprint,  // the generic pixel footprint: a Gaussian of 0.4 input pixels (the default)
    box,        // area averaging: each input pixel the mean of its footprint
    bicubic,    // Keys' cubic with a = −0.5 (Catmull–Rom), photo editors' "bicubic"
    lanczos3,   // sinc windowed by sinc over ±3 input pixels
};

// "footprint", "box", "bicubic", "lanczos3", and back; nullopt for any other name.
const char* assumedKernelName(AssumedKernel kernel);
std::optional<AssumedKernel> parseAssumedKernel(const std::string& name);
// The names, comma-separated, for messages and help.
std::string assumedKernelNames();

// The kernel's weight at distance x in input pixels, at its full width (before normalising).
double kernelWeight(AssumedKernel kernel, double x);
// How far from its centre the kernel reaches, in input pixels, at its full width.
double kernelSupport(AssumedKernel kernel);

}  // namespace ddt
