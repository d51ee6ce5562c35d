// Whether a peer magnifier samples as ddtup does, output pixel X at input coordinate
// (X + 0.5) / s − 0.5: a peer on another grid would be scored for its shift, not its quality
// (a quarter of an input pixel at ×2 costs about a dB).
#pragma once

#include <cstdint>
#include <functional>
#include <initializer_list>

#include "image.h"

namespace bench {

// A magnifier: `input` to width × height.
using Magnifier = std::function<ddt::Image(const ddt::Image& input, uint32_t width, uint32_t height)>;

// The largest |sampled − expected| input coordinate, in input pixels, of a horizontal and a
// vertical ramp magnified by each of `scales`, away from the borders (where a peer's
// clamping or mirroring bends the ramp).
double rampMisalignment(const Magnifier& magnify, std::initializer_list<double> scales);

}  // namespace bench
