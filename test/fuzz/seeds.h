// Valid small images of each format, made afresh by every run (no binary seeds in the
// repository): most by OpenImageIO's writers, in several variants per format (channels,
// depths, compressions, tiles, interlacing, progressive scans), the rest by hand where its
// writers make no such file (PNG with a palette or interlaced, BMP with 1- and 4-bit palettes
// or RLE, colour-mapped Targa, PFM). Small (8-40 pixels a side), so each decode is quick.
#pragma once

#include <string>
#include <vector>

namespace fuzz {

struct Seed {
    std::string variant;    // what kind of file it is: "rgb8-interlaced"
    std::string extension;  // with the dot; PNM's depends on the variant
    std::string bytes;
};

// The seeds of `format` (a name from formats.h), written through files in `folder`.
// Throws std::runtime_error when a writer fails: the fuzzer cannot run without its seeds.
std::vector<Seed> makeSeeds(const std::string& format, const std::string& folder);

// A test pattern: a diagonal edge, stripes and a little noise, alpha from clear to opaque.
// `range` scales the colour (above 1 for the float formats).
float patternSample(int x, int y, int channel, int channels, float range);

}  // namespace fuzz
