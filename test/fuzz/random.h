// The fuzzer's one source of randomness. Every damaged input has its own generator, seeded
// from the run's --seed and the input's number, so any input can be made again alone.
// std::mt19937_64 and the arithmetic below are fully specified, unlike the standard
// distributions, so a seed means the same inputs with every standard library.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace fuzz {

class Random {
public:
    explicit Random(uint64_t seed) : engine_(seed) {}

    // The generator of input `index` of a run seeded with `seed`.
    static Random forInput(uint64_t seed, uint64_t index) { return Random(mix(mix(seed) ^ index)); }

    // 0 … n − 1 (0 when n is 0).
    uint64_t below(uint64_t n) { return n ? engine_() % n : 0; }
    // lo … hi, both included.
    int64_t between(int64_t lo, int64_t hi) { return lo + int64_t(below(uint64_t(hi - lo) + 1)); }
    // True with probability `percent` / 100.
    bool percent(unsigned percent) { return below(100) < percent; }
    uint8_t byte() { return uint8_t(engine_()); }
    std::string bytes(size_t count) {
        std::string out(count, '\0');
        for (char& c : out) c = char(byte());
        return out;
    }
    template <class T>
    const T& pick(const std::vector<T>& items) {
        return items[below(items.size())];
    }

private:
    // SplitMix64's finaliser: neighbouring seeds give unrelated generators.
    static uint64_t mix(uint64_t x) {
        x += 0x9E3779B97F4A7C15ull;
        x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
        x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
        return x ^ (x >> 31);
    }

    std::mt19937_64 engine_;
};

}  // namespace fuzz
