// Division of 32-bit integers by a divisor fixed at run time (the image width, to turn a vertex
// id into its row and column), as one multiplication instead of a division instruction.
#pragma once

#include <cassert>
#include <cstdint>

namespace ddt {

class DivideBy {
public:
    // divisor >= 2.
    explicit DivideBy(uint32_t divisor) : divisor_(divisor), reciprocal_(UINT64_MAX / divisor + 1) { assert(divisor >= 2); }

    // ⌊n / d⌋ for every 32-bit n: the reciprocal ⌈2^64 / d⌉ is (2^64 + e) / d with 0 ≤ e < d,
    // so n · reciprocal / 2^64 exceeds n / d by n · e / (d · 2^64) < 1 / d, too little to pass
    // the next integer (n / d is at most 1 − 1 / d above its floor).
    uint32_t quotient(uint32_t n) const { return uint32_t((unsigned __int128)n * reciprocal_ >> 64); }
    uint32_t remainder(uint32_t n) const { return n - quotient(n) * divisor_; }

private:
    uint32_t divisor_;
    uint64_t reciprocal_;
};

}  // namespace ddt
