// Floats to 8- and 16-bit codes the way ddtup's PNG and JPEG writers make them
// (core/io/sample_quantise.h): a row made piece by piece is the row made whole.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "sample_quantise.h"

namespace {

using namespace ddt;

// Values of every kind a row meets: in and out of [0, 1], on and beside each rounding
// boundary (including the float whose product with Max is the float below 0.5 — the one the
// row's two ways make different codes of), zeros of both signs and NaN.
template <typename Sample>
std::vector<float> awkwardValues(std::mt19937& rng, size_t n) {
    constexpr float kMax = float(std::numeric_limits<Sample>::max());
    std::uniform_real_distribution<float> any(-0.2f, 1.2f);
    std::uniform_int_distribution<int> code(0, int(kMax));
    const float below_half = std::nextafter(0.5f, 0.0f) / kMax;
    std::vector<float> values(n);
    for (float& v : values) {
        switch (rng() % 6) {
        case 0: v = any(rng); break;
        case 1: v = (float(code(rng)) + 0.5f) / kMax; break;
        case 2: v = std::nextafter((float(code(rng)) + 0.5f) / kMax, 0.0f); break;
        case 3: v = below_half; break;
        case 4: v = rng() % 2 ? -0.0f : 0.0f; break;
        default: v = std::numeric_limits<float>::quiet_NaN();
        }
    }
    return values;
}

template <typename Sample>
void checkPieces() {
    std::mt19937 rng(11);
    for (size_t n : {1u, 3u, 4u, 7u, 64u, 301u, 1026u}) {
        CAPTURE(n);
        const std::vector<float> values = awkwardValues<Sample>(rng, n);
        std::vector<Sample> whole(n), pieces(n, Sample(1));
        quantiseRow(values.data(), whole.data(), n);
        // Random cuts, so that pieces start and end at every place modulo 4 and across the
        // row's last n % 4 values.
        for (size_t begin = 0; begin < n;) {
            const size_t end = std::min(n, begin + 1 + rng() % 9);
            quantiseRowPart(values.data() + begin, pieces.data() + begin, begin, end, n);
            begin = end;
        }
        CHECK(pieces == whole);
    }
}

TEST_CASE("sample quantise: a row made piece by piece is the row made whole") {
    checkPieces<uint8_t>();
    checkPieces<uint16_t>();
}

}  // namespace
