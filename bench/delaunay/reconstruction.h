// The reconstruction table's methods: an image rebuilt at its own size from its known pixels
// only (the others are zeroed before any method sees them), scored against the full image.
// Methods: linear interpolation on the plain Delaunay mesh of the known pixels; DDT, the same
// mesh optimised by the serial reference (or the Vulkan backend); CGAL's natural-neighbour
// interpolation; for blobs, G'MIC's inpainting.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "backend.h"
#include "image.h"

namespace bench {

struct Reconstruction {
    std::string method;
    std::string failure;  // "" if it ran ("gmic missing" …)
    double seconds = 0.0;      // wall clock
    double cpu_seconds = 0.0;  // CPU time of every thread (and of G'MIC's process)
    uint64_t flips = 0;          // DDT only
    double psnr_all = 0.0;       // dB over every pixel (core/metrics.h: 8-bit values, colour channels)
    double psnr_unknown = 0.0;   // dB over the unknown pixels only
};

struct ReconstructionOptions {
    bool variance = true;               // also DDT with the variance cost
    bool gmic = true;                   // G'MIC's peers, for blobs
    ddt::Backend* vulkan = nullptr;     // also DDT on this Vulkan backend (a row "DDT, sederberg, Vulkan")
    // "" or the start of a path: each method's image is also written to it + the method's name
    // in lower case, words joined by "-", + ".png" (the known pixels alone as "known").
    std::string pictures;
};

// "DDT, sederberg" → "ddt-sederberg": a name for files.
std::string slugOf(const std::string& method);

// Every method on `original` knowing `known` (ids y · width + x, ascending; the 4 corners
// among them), timed and scored. `blobs` adds the G'MIC rows.
std::vector<Reconstruction> reconstructAll(const ddt::Image& original, const std::vector<uint32_t>& known, bool blobs,
                                           const ReconstructionOptions& options);

}  // namespace bench
