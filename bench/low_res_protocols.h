// How the protocol tables make a low-resolution input from an original (bench/README.md):
// - A, the paper's: log2(f) bilinear halvings (protocol.h makeLowRes). ×2.5 is no power of
//   two, so there A is one OIIO `triangle` resize by 1/2.5 (the tent OIIO widens to the
//   source pixels when shrinking, as one halving does).
// - B: exact area averaging (area_average.h), the model of a camera pixel or a box filter.
// - JPEG: A's image, then stored as JPEG of quality 85 and read back (jpeg_roundtrip.h).
// - bicubic: one OIIO `catmull-rom` resize by 1/f (Keys' cubic, a = −0.5: editors' bicubic).
// - camera: a Gaussian blur of σ = 0.4·f sampled at the pixels' centres, then noise of
//   σ = 1/255 (camera_model.h).
// - a held-back filter (--protocol-filter NAME): one OIIO resize by 1/f with that filter.
// Every variant computes in float and rounds to 8 bits once; originals are cropped (centred)
// to a multiple of the factor's numerator, so the low-resolution size is exact (5 for ×2.5).
#pragma once

#include <string>
#include <vector>

#include "image.h"
#include "magnification.h"

namespace bench {

enum class ProtocolKind { Halvings, AreaAverage, Jpeg, OiioResize, Camera };

struct Protocol {
    std::string key;    // "A", "B", "A+JPEG85", "bicubic", "camera", "C"
    std::string label;  // for the report
    ProtocolKind kind = ProtocolKind::Halvings;
    std::string filter;  // OiioResize: the OIIO filter name
    std::vector<Magnification> factors;
};

// The JPEG quality of protocol A+JPEG.
constexpr int kProtocolJpegQuality = 85;

// The protocols and their factors: A and B at ×2, ×2.5, ×4, ×8, A+JPEG, bicubic and camera at
// ×2, ×4, ×8, and C with `held_back_filter` at A's factors when it is not empty. --quick: fewer
// factors.
std::vector<Protocol> benchProtocols(const std::string& held_back_filter, bool quick);

// One sentence per protocol for the report.
std::string describeProtocol(const Protocol& protocol);

// `original` cropped (centred) to a multiple of factor.numerator per side.
ddt::Image cropForFactor(const ddt::Image& original, Magnification factor);

// The 8-bit low-resolution input of `cropped` (from cropForFactor) under `protocol`.
ddt::Image protocolLowRes(const Protocol& protocol, const ddt::Image& cropped, Magnification factor);

// True if OIIO knows a 2D filter of this name.
bool isOiioFilter(const std::string& name);

}  // namespace bench
