// Seed files written byte by byte, for the layouts OpenImageIO 2.4's writers never produce.
#pragma once

#include <vector>

#include "seeds.h"

namespace fuzz {

std::vector<Seed> handmadePngSeeds();    // palette + tRNS, 4-bit palette interlaced, 1-bit grey, RGB interlaced
std::vector<Seed> handmadeBmpSeeds();    // 1- and 4-bit palettes, RLE8, RLE4, 16-bit bit fields, top-down
std::vector<Seed> handmadeTargaSeeds();  // colour-mapped, colour-mapped RLE, 15-bit true colour
std::vector<Seed> handmadePnmSeeds();    // PFM colour and grey, little and big endian

}  // namespace fuzz
