#include "interesting.h"

#include <vector>

namespace fuzz {

namespace {

uint64_t maxOf(int bits) { return bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1; }

}  // namespace

uint64_t interestingValue(Random& random, uint64_t current, int bits) {
    const uint64_t max = maxOf(bits);
    std::vector<uint64_t> values = {0, 1, 2, 3, 4, 7, 8, 15, 16, 17, 31, 32, 63, 64, 127, 128, 255, 256, 257,
                                    1023, 1024, 4095, 4096, 16383, 16384, 16385, 32767, 32768, 65535, 65536,
                                    0x7FFFFFFF, 0x80000000, 0xFFFFFFFF, 0x7FFFFFFFFFFFFFFF, 0x8000000000000000,
                                    ~uint64_t(0), current - 1, current + 1, current * 2, current / 2,
                                    random.below(current * 2 + 16)};
    if (bits <= 16) values.push_back(max - 1);
    std::vector<uint64_t> fitting;
    for (uint64_t value : values)
        if (value <= max && value != current) fitting.push_back(value);
    return fitting.empty() ? 0 : random.pick(fitting);
}

int64_t interestingSigned(Random& random, int64_t current, int bits) {
    if (random.percent(30)) {
        const int64_t negatives[] = {-1, -2, -current, -current - 1, -65536, -2147483647, INT32_MIN, INT64_MIN};
        const int64_t value = negatives[random.below(std::size(negatives))];
        const int64_t min = bits >= 64 ? INT64_MIN : -(int64_t(1) << (bits - 1));
        return value < min ? min : value;
    }
    const uint64_t value = interestingValue(random, uint64_t(current), bits - 1);
    return int64_t(value);
}

std::string badNumberText(Random& random, uint64_t current) {
    const std::string texts[] = {"0",    "1",   "-1",   "65536", "2147483647", "2147483648", "4294967296",
                                 "99999999999999999999", "+5", "1.5", "0x10", "a", "1e3", "00000000000000000000019",
                                 "-0",   "",    std::string(5000, '9')};
    if (random.percent(30)) return std::to_string(interestingValue(random, current, 32));
    return texts[random.below(std::size(texts))];
}

}  // namespace fuzz
