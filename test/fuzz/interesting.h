// Values that hit limits, signs and off-by-one edges, for header fields.
#pragma once

#include <cstdint>
#include <string>

#include "random.h"

namespace fuzz {

// A value for an unsigned field of `bits` bits (8 to 64) that holds `current`: 0, 1, powers
// of two and their neighbours, the field's largest values, and current ± 1, × 2, / 2.
// Between 65536 and 2^31 only current-derived values are offered: a size field set there
// next to a small one passes ddtup's 2^28-pixel limit and makes it fill gigabytes with zeros
// before the decoder can complain, which costs time and memory and finds nothing.
uint64_t interestingValue(Random& random, uint64_t current, int bits);

// The same for a two's complement field, negatives included (BMP sizes, EXR windows).
int64_t interestingSigned(Random& random, int64_t current, int bits);

// A number written as text the way decimal parsers get wrong: signs, overflow, fractions,
// hexadecimal, letters, nothing, thousands of digits; or an interesting value (PNM, HDR).
std::string badNumberText(Random& random, uint64_t current);

}  // namespace fuzz
