// Volume geometry (core/volume/volume.h): spacing, resampled sizes and affines, the size
// limits. Every expected number is worked out by hand in the comments.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "volume.h"

using ddt::Affine;

namespace {

Affine diagonalAffine(double sx, double sy, double sz, double ox, double oy, double oz) {
    Affine a;
    a.m = {{{sx, 0, 0, ox}, {0, sy, 0, oy}, {0, 0, sz, oz}}};
    return a;
}

// A rotation by 30° about z of spacing (0.5, 0.5, 2.5) at (10, 20, 30): columns
// (0.5 cos 30°, 0.5 sin 30°, 0), (−0.5 sin 30°, 0.5 cos 30°, 0), (0, 0, 2.5).
Affine obliqueAffine() {
    const double c = std::sqrt(3.0) / 2, s = 0.5;
    Affine a;
    a.m = {{{0.5 * c, -0.5 * s, 0, 10}, {0.5 * s, 0.5 * c, 0, 20}, {0, 0, 2.5, 30}}};
    return a;
}

// world = A · (index, 1), computed here.
std::array<double, 3> worldOf(const Affine& a, double x, double y, double z) {
    std::array<double, 3> w{};
    for (int r = 0; r < 3; ++r) w[r] = a.m[r][0] * x + a.m[r][1] * y + a.m[r][2] * z + a.m[r][3];
    return w;
}

}  // namespace

TEST_CASE("volume io: spacingOf is the length of each affine column", "[volume-io]") {
    const std::array<double, 3> diagonal = ddt::spacingOf(diagonalAffine(0.5, 0.5, 2.5, 10, 20, 30));
    CHECK(diagonal[0] == 0.5);
    CHECK(diagonal[1] == 0.5);
    CHECK(diagonal[2] == 2.5);
    // A rotation changes no length; a flipped axis (negative step) neither.
    const std::array<double, 3> oblique = ddt::spacingOf(obliqueAffine());
    CHECK(oblique[0] == Approx(0.5).margin(1e-15));
    CHECK(oblique[1] == Approx(0.5).margin(1e-15));
    CHECK(oblique[2] == 2.5);
    CHECK(ddt::spacingOf(diagonalAffine(-0.75, 1, 1, 0, 0, 0))[0] == 0.75);
}

TEST_CASE("volume io: resampledSize rounds f·n and keeps at least one voxel", "[volume-io]") {
    CHECK(ddt::resampledSize({4, 3, 2}, {2, 2, 2.5}) == std::array<uint32_t, 3>{8, 6, 5});
    // 1.5 · 3 = 4.5 rounds up to 5; 0.1 · 3 = 0.3 would be 0 voxels: 1.
    CHECK(ddt::resampledSize({3, 3, 3}, {1.5, 0.1, 1}) == std::array<uint32_t, 3>{5, 1, 3});
}

TEST_CASE("volume io: a 4×3×2 volume at (10, 20, 30) resampled to 8×6×5 keeps its box", "[volume-io]") {
    // Spacing n·s/m: 4·0.5/8 = 0.25, 3·0.5/6 = 0.25, 2·2.5/5 = 1.
    // Origin: half a new voxel minus half an old one along each axis:
    //   x: 10 + 0.125 − 0.25 = 9.875, y: 20 + 0.125 − 0.25 = 19.875, z: 30 + 0.5 − 1.25 = 29.25.
    const Affine out = ddt::resampledAffine(diagonalAffine(0.5, 0.5, 2.5, 10, 20, 30), {4, 3, 2}, {8, 6, 5});
    const double expected[3][4] = {{0.25, 0, 0, 9.875}, {0, 0.25, 0, 19.875}, {0, 0, 1, 29.25}};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) {
            INFO("row " << r << " column " << c);
            CHECK(out.m[r][c] == Approx(expected[r][c]).margin(1e-12));
        }
    // The boxes' corners agree: the input's first voxel starts at 10 − 0.25 = 9.75 along x,
    // the output's at 9.875 − 0.125; its last ends at 10 + 3·0.5 + 0.25 = 11.75 along x and at
    // 30 + 2.5 + 1.25 = 33.75 along z.
    CHECK(out.m[0][3] - 0.5 * out.m[0][0] == Approx(9.75));
    CHECK(out.m[0][3] + 7.5 * out.m[0][0] == Approx(11.75));
    CHECK(out.m[2][3] + 4.5 * out.m[2][2] == Approx(33.75));
}

TEST_CASE("volume io: an oblique affine resampled puts each output voxel where the glossary says", "[volume-io]") {
    // Output voxel i' lies at input index (i' + 0.5)·n/m − 0.5 along each axis; both affines
    // must place it at the same world point.
    const Affine in = obliqueAffine();
    const std::array<uint32_t, 3> n{4, 3, 2}, m{7, 9, 5};
    const Affine out = ddt::resampledAffine(in, n, m);
    for (uint32_t x : {0u, 3u, 6u})
        for (uint32_t y : {0u, 8u})
            for (uint32_t z : {0u, 2u, 4u}) {
                const double ix = (x + 0.5) * 4 / 7 - 0.5, iy = (y + 0.5) * 3 / 9 - 0.5, iz = (z + 0.5) * 2 / 5 - 0.5;
                const std::array<double, 3> expected = worldOf(in, ix, iy, iz), got = worldOf(out, x, y, z);
                INFO("output voxel " << x << ", " << y << ", " << z);
                for (int r = 0; r < 3; ++r) CHECK(got[r] == Approx(expected[r]).margin(1e-12));
            }
    CHECK(ddt::inputIndexOf(6, 4, 7) == Approx(6.5 * 4 / 7 - 0.5));
}

TEST_CASE("volume io: volumeSizeProblem refuses planes and sizes past the limits", "[volume-io]") {
    CHECK(ddt::volumeSizeProblem({4, 3, 2}).empty());
    CHECK(ddt::volumeSizeProblem({512, 512, 1}).find("not a volume") != std::string::npos);
    CHECK(ddt::volumeSizeProblem({1, 2, 2}).find("1 × 2 × 2 voxels") != std::string::npos);
    CHECK(ddt::volumeSizeProblem({65536, 2, 2}).empty());
    CHECK(ddt::volumeSizeProblem({65537, 2, 2}).find("65536") != std::string::npos);
    // 2048 · 1024 · 1024 = 2^31 is allowed, one slice more is not.
    CHECK(ddt::volumeSizeProblem({2048, 1024, 1024}).empty());
    CHECK(ddt::volumeSizeProblem({2048, 1024, 1025}).find("2^31") != std::string::npos);
    CHECK(ddt::kMaxVolumeVoxels == 2147483648ull);
}
