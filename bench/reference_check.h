// The reference numbers of ../shared/PLATFORM.md for the bundled sets: a straightforward
// serial DDT and OIIO's filters under this protocol, as means of per-image PSNR and SSIM.
// A full run on the bundled data compares itself with them, which checks the protocol, the
// metrics and the serial DDT together.
#pragma once

#include <string>

#include "results.h"

namespace bench {

// A Markdown table of measured against reference values, with the tolerance each is held
// to, or "" when the run is not a full run over the bundled 12 + 8 images.
std::string referenceCheckMarkdown(const BenchResults& results);

// One line per comparison outside its tolerance; empty when all agree (or no check ran).
std::vector<std::string> referenceMismatches(const BenchResults& results);

}  // namespace bench
