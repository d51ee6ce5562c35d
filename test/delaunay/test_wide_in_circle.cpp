// glsl/delaunay/in_circle.h, the device's in-circle test in two 64-bit words, compiled here as
// C++ and compared with predicates.h's __int128 on the values that stress it most.
#include <catch2/catch.hpp>

#include <random>

#include "delaunay/in_circle.h"
#include "predicates.h"

using namespace ddt;

namespace {

int signOf(__int128 x) { return x > 0 ? 1 : x < 0 ? -1 : 0; }

}  // namespace

TEST_CASE("wide in-circle: the product of two words is exact below 2^55 each", "[delaunay]") {
    std::mt19937_64 rng(31);
    const uint64_t top = (uint64_t(1) << 55) - 1;
    std::uniform_int_distribution<uint64_t> any(0, top), high(top - (1u << 20), top);
    for (int i = 0; i < 100000; ++i) {
        const uint64_t x = i % 2 ? any(rng) : high(rng), y = i % 3 ? any(rng) : high(rng);
        const unsigned __int128 exact = (unsigned __int128)x * y;
        const WideUnsigned w = wideProduct(x, y);
        CHECK(w.high == uint64_t(exact >> 64));
        CHECK(w.low == uint64_t(exact));
    }
    const WideUnsigned w = wideProduct(top, top);
    CHECK((((unsigned __int128)w.high << 64) | w.low) == (unsigned __int128)top * top);
}

TEST_CASE("wide in-circle: its sign and tie-break are predicates.h's", "[delaunay]") {
    std::mt19937_64 rng(32);
    const int32_t top = (1 << 26) - 1;
    std::uniform_int_distribution<int32_t> anywhere(0, top), near_top(top - (1 << 12), top), low(0, 1 << 12);
    std::uniform_int_distribution<int32_t> unit(-1, 1);
    int zeros = 0;
    for (int i = 0; i < 200000; ++i) {
        Position p[4];
        for (Position& q : p) {
            switch (i % 4) {
            case 0: q = {anywhere(rng), anywhere(rng)}; break;
            case 1: q = {near_top(rng), near_top(rng)}; break;
            case 2: q = {i % 2 ? low(rng) : top - low(rng), i % 8 < 4 ? low(rng) : top - low(rng)}; break;
            default: q = {(low(rng) % 4) * (top / 3), (low(rng) % 4) * (top / 3)}; break;  // a coarse lattice: ties
            }
        }
        if (i % 4 == 2) p[3] = {std::clamp(p[0].x + unit(rng), 0, top), std::clamp(p[0].y + unit(rng), 0, top)};
        if (orient(p[0], p[1], p[2]) < 0) std::swap(p[1], p[2]);
        const int sign = signOf(inCircleDeterminant(p[0], p[1], p[2], p[3]));
        CHECK(inCircleSign(p[0], p[1], p[2], p[3]) == sign);
        const bool distinct = !(p[0] == p[1] || p[0] == p[2] || p[0] == p[3] || p[1] == p[2] || p[1] == p[3] || p[2] == p[3]);
        if (orient(p[0], p[1], p[2]) > 0 && distinct) {
            CHECK(inCirclePerturbed(p[0], p[1], p[2], p[3]) == inCircle(p[0], p[1], p[2], p[3]));
            zeros += sign == 0;
        }
    }
    CHECK(zeros > 100);
}
