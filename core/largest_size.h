// The largest of the sizes noted so far, from any thread, for --stats' memory lines: the
// largest block the process asked for and the largest device buffer. A whole-image buffer on
// the image path shows there.
#pragma once

#include <atomic>
#include <cstdint>

namespace ddt {

class LargestSize {
public:
    constexpr LargestSize() = default;

    void note(uint64_t size) {
        uint64_t largest = largest_.load(std::memory_order_relaxed);
        while (size > largest && !largest_.compare_exchange_weak(largest, size, std::memory_order_relaxed)) {
        }
    }
    uint64_t largest() const { return largest_.load(std::memory_order_relaxed); }

private:
    std::atomic<uint64_t> largest_{0};
};

}  // namespace ddt
