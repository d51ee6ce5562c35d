// G'MIC's inpainting as a peer for the blobs (the `gmic` command-line tool, run as a
// subprocess on temporary PNG files). The mask convention, from G'MIC 2.9.4's reference
// (man gmic): the mask is a second image of the same size, non-zero where pixels are to be
// inpainted; `inpaint_pde[0] [1]` fills them by multiscale transport-diffusion,
// `inpaint[0] [1],patch_size` by patch-based reconstruction.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image.h"

namespace bench {

struct GmicResult {
    std::string failure;  // "" on success; "gmic missing" when the tool is not on PATH
    ddt::Image image;     // the inpainted image, 8-bit values as floats
    // The gmic process, from start to exit (its PNG decoding and encoding included): wall
    // clock, and its CPU time (user + system, all its threads).
    double seconds = 0.0, cpu_seconds = 0.0;
};

// Whether `gmic` is on PATH.
bool gmicAvailable();

// Inpaints the pixels of `image` not in `known` (ids ascending) with the G'MIC command
// `command` ("inpaint_pde", or "inpaint" with arguments after the mask: ",7").
GmicResult gmicInpaint(const ddt::Image& image, const std::vector<uint32_t>& known, const std::string& command,
                       const std::string& arguments);

}  // namespace bench
