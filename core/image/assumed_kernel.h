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
    mixed,      // an unknown downscale (the default): the footprint and bicubic, kMixedFootprintShare of the footprint
    footprint,  // the generic pixel footprint of a camera or an averaging resize: a Gaussian of 0.4 input pixels
    box,        // area averaging: each input pixel the mean of its footprint
    bicubic,    // Keys' cubic with a = −0.5 (Catmull–Rom), photo editors' "bicubic"
    lanczos3,   // sinc windowed by sinc over ±3 input pixels
};

// The footprint's share of `mixed`, whose taps are this much of the footprint's and the rest
// of bicubic's (core/image/reconstruct.h). Chosen by the lowest row on held-out photographs,
// half a (bench/README.md, "Mixed assumption"): against the footprint alone, with the
// fallback, input made by one Lanczos3 shrink gains 0.07–0.13 dB and by a bicubic one
// 0.03–0.06, by bilinear halvings or a camera loses 0.04–0.09; the lowest row rose from
// +0.02 to +0.12 dB over Lanczos3 (0.7: +0.11).
constexpr double kMixedFootprintShare = 0.5;

// What the default, `--assume auto`, assumes of an input read from a file of `format_name`
// (OIIO's name; "" for an image made in memory): footprint for "jpeg", mixed for any other.
// A JPEG file is most often a camera's picture, the footprint's model, and its compression
// noise favours the gentler assumption. Measured on held-out photographs made by bilinear
// halvings and stored as JPEG 85, with the fallback (bench/README.md, "Automatic
// assumption"): the footprint scored 0.03–0.04 dB above mixed on half a, which chose it, and
// 0.07–0.09 on half b.
AssumedKernel automaticAssumption(const std::string& format_name);
// The name of that choice on the command line.
inline constexpr const char* kAutomaticAssumption = "auto";

// "mixed", "footprint", "box", "bicubic", "lanczos3", and back; nullopt for any other name.
const char* assumedKernelName(AssumedKernel kernel);
std::optional<AssumedKernel> parseAssumedKernel(const std::string& name);
// The names, comma-separated, for messages and help.
std::string assumedKernelNames();

// The kernel's weight at distance x in input pixels, at its full width (before normalising),
// and how far from its centre it reaches; `mixed` is a mixture of two kernels' normalised
// taps, not one kernel: 0 for both.
double kernelWeight(AssumedKernel kernel, double x);
double kernelSupport(AssumedKernel kernel);

}  // namespace ddt
