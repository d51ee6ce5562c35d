// A magnification factor as a ratio of integers, so that ×2.5 is exact: an original cropped
// to a multiple of `numerator` per side has a low-resolution image of exactly
// side · denominator / numerator pixels.
#pragma once

#include <cstdint>
#include <string>

namespace bench {

struct Magnification {
    uint32_t numerator = 2;
    uint32_t denominator = 1;

    double value() const { return double(numerator) / double(denominator); }
    bool integral() const { return denominator == 1; }
    // "2", "2.5": how tables and file names show it.
    std::string name() const;
    // The low-resolution side for an original side that is a multiple of `numerator`.
    uint32_t lowSide(uint32_t side) const { return side / numerator * denominator; }
};

bool operator==(const Magnification& a, const Magnification& b);

}  // namespace bench
