// The protocol tables' measurements ("Beyond Lanczos"): every original under every
// protocol (low_res_protocols.h) at each of its factors, magnified by every column of
// protocol_methods.h and scored with PSNR and SSIM (core/metrics.h), GMSD (gmsd.h) and
// overshoot (overshoot.h). Also writes a crop strip per image: original, Lanczos3, plain and
// consistent CPU DDT.
#pragma once

#include <string>
#include <vector>

#include "image.h"
#include "results.h"

namespace bench {

struct StudyImage {
    std::string set;
    std::string name;
    ddt::Image original;
};

// Fills results.protocol_images (results.protocols and results.upscalers must be set) and
// writes the strips to `crops_dir`. Returns false if the strips could not be labelled.
bool runProtocolStudy(BenchResults& results, const std::vector<StudyImage>& images, const std::string& crops_dir);

}  // namespace bench
