// Which pixels of an image the reconstruction table knows: a share of random pixels, or all
// but some random discs ("blobs"). Every pattern keeps the 4 corners, so the known pixels'
// convex hull is the whole frame and every method interpolates everywhere (none has to
// extrapolate).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

struct SamplePattern {
    std::string name;   // "random 5 %", "blobs 15 %"
    double share = 0.0;  // random: the share of pixels known; blobs: the share removed
    bool blobs = false;
};

// The known pixels' ids (y · width + x), ascending. Random: round(share · w · h) distinct
// pixels plus the corners. Blobs: discs of radius 2–6 % of the shorter side at random centres
// until `share` of the pixels lie in one; those are unknown. Both seeded by `seed`.
std::vector<uint32_t> knownPixelsOf(const SamplePattern& pattern, uint32_t width, uint32_t height, uint64_t seed);

}  // namespace bench
