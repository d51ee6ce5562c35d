// Fig. 13: runtime against input size at ×4 (the paper's 400 percent). Two datasets, as the
// paper's: "resized" is one image resized to n × n for n from 64 up by factors of √2 (its
// Dataset 2), "set" is every original of every set at its own size (its Dataset 1).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image.h"
#include "results.h"

namespace bench {

// Fig. 13's magnification factor.
inline constexpr uint32_t kScalingFactor = 4;

// 64, 91, 128, 181, … up to and including max_side when it is on the √2 ladder.
std::vector<uint32_t> scalingSides(uint32_t max_side);

// `image` resized to side × side (OIIO's default filters) and rounded to 8 bits.
ddt::Image resizedSquare(const ddt::Image& image, uint32_t side);

// Every available method run on `input` magnified ×4, rows rendered in bands and dropped.
std::vector<ScalingResult> measureScaling(const std::vector<DdtMethod>& methods, const std::string& dataset,
                                          const std::string& image_name, const ddt::Image& input, uint32_t warmups,
                                          uint32_t repeats);

}  // namespace bench
