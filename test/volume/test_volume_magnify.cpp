// The volume pipeline's core (core/volume/volume_magnify.h): bricks that partition the output
// and hold their samples, a linear field reproduced through bricks, one brick equal to the
// whole-volume path.
#include <catch2/catch.hpp>

#include <cmath>

#include "tet_cost.h"
#include "tet_lawson.h"
#include "tet_mesh.h"
#include "tet_resample.h"
#include "volume.h"
#include "volume_magnify.h"

using namespace ddt;

namespace {

Volume volumeOf(std::array<uint32_t, 3> size, double (*f)(double, double, double)) {
    Volume volume;
    volume.size = size;
    volume.index_to_world.m = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};
    for (uint32_t z = 0; z < size[2]; ++z)
        for (uint32_t y = 0; y < size[1]; ++y)
            for (uint32_t x = 0; x < size[0]; ++x) volume.values.push_back(float(f(x, y, z)));
    return volume;
}

double linear(double x, double y, double z) { return x + 2 * y + 3 * z; }

// A ball of 1 in 0, its centre off the grid so that its surface cuts the cells unevenly.
double ball(double x, double y, double z) {
    const double dx = x - 7.3, dy = y - 6.6, dz = z - 5.9;
    return dx * dx + dy * dy + dz * dz < 20.0 ? 1.0 : 0.0;
}

// Input index of output voxel i along an axis of n in, m out, clamped to the voxel centres' box.
double clampedInputIndex(uint32_t i, uint32_t n, uint32_t m) {
    return std::clamp((i + 0.5) * n / m - 0.5, 0.0, double(n - 1));
}

}  // namespace

TEST_CASE("volume magnify: the bricks' windows partition the output and hold their samples", "[volume-magnify]") {
    const std::array<uint32_t, 3> size = {11, 7, 5};
    for (const std::array<uint32_t, 3>& new_size : {std::array<uint32_t, 3>{22, 14, 10}, {19, 7, 13}, {11, 7, 5}})
        for (uint32_t side : {0u, 1u, 3u, 4u, 100u})
            for (uint32_t margin : {0u, 1u, 3u}) {
                INFO("side " << side << " margin " << margin << " out " << new_size[0] << "x" << new_size[1] << "x" << new_size[2]);
                std::vector<int> count(size_t(new_size[0]) * new_size[1] * new_size[2], 0);
                for (const VolumeBrick& brick : volumeBricks(size, new_size, side, margin)) {
                    const TetResampleWindow& w = brick.window;
                    for (int a = 0; a < 3; ++a) {
                        REQUIRE(brick.mesh_size[a] >= 2);
                        REQUIRE(w.vertex_offset[a] + brick.mesh_size[a] <= size[a]);
                        for (uint32_t i = w.out_begin[a]; i < w.out_end[a]; ++i) {
                            // Each sample inside the brick's vertices, and on its high side
                            // only where that is the volume's (the tie rule's push points
                            // backwards there alone).
                            const double u = clampedInputIndex(i, size[a], new_size[a]);
                            const uint32_t high = w.vertex_offset[a] + brick.mesh_size[a] - 1;
                            REQUIRE(u >= w.vertex_offset[a]);
                            REQUIRE(u <= high);
                            if (u == high) REQUIRE(high == size[a] - 1);
                        }
                    }
                    for (uint32_t z = w.out_begin[2]; z < w.out_end[2]; ++z)
                        for (uint32_t y = w.out_begin[1]; y < w.out_end[1]; ++y)
                            for (uint32_t x = w.out_begin[0]; x < w.out_end[0]; ++x)
                                ++count[x + size_t(new_size[0]) * (y + size_t(new_size[1]) * z)];
                }
                CHECK(std::count(count.begin(), count.end(), 1) == std::ptrdiff_t(count.size()));
            }
}

TEST_CASE("volume magnify: a linear field comes through bricks exactly", "[volume-magnify]") {
    const std::array<uint32_t, 3> size = {9, 7, 6};
    const Volume volume = volumeOf(size, linear);
    for (const std::array<uint32_t, 3>& new_size : {std::array<uint32_t, 3>{18, 14, 12}, {15, 20, 6}})
        for (uint32_t side : {2u, 3u, 5u})
            for (uint32_t margin : {0u, 2u}) {
                VolumeMagnifyOptions options;
                options.brick_side = side;
                options.margin = margin;
                VolumeMagnifyStats stats;
                const std::vector<float> out = magnifyVolumeValues(volume, new_size, options, stats);
                CHECK(stats.bricks > 1);
                double worst = 0.0;
                for (uint32_t z = 0; z < new_size[2]; ++z)
                    for (uint32_t y = 0; y < new_size[1]; ++y)
                        for (uint32_t x = 0; x < new_size[0]; ++x) {
                            const double want = linear(clampedInputIndex(x, size[0], new_size[0]),
                                                       clampedInputIndex(y, size[1], new_size[1]),
                                                       clampedInputIndex(z, size[2], new_size[2]));
                            const float got = out[x + size_t(new_size[0]) * (y + size_t(new_size[1]) * z)];
                            REQUIRE(!std::isnan(got));  // every voxel resampled
                            worst = std::max(worst, std::abs(got - want));
                        }
                // Values up to 29 stored as float: a few of float's ulps (2^-19 at 16–32).
                CHECK(worst < 1e-5);
            }
}

TEST_CASE("volume magnify: one brick is the whole volume's optimize and resample", "[volume-magnify]") {
    const std::array<uint32_t, 3> size = {14, 13, 12}, new_size = {28, 26, 24};
    const Volume volume = volumeOf(size, ball);
    for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
        TetMesh mesh = kuhnTetMesh(size);
        TetLawsonOptions lawson;
        lawson.weight = weight;
        const TetLawsonStats expected = optimizeTetMeshSerial(mesh, tetCostFieldOf(volume), lawson);
        const std::vector<float> want = resampleTets(mesh, volume.values, new_size);
        REQUIRE(expected.flipCount() > 0);
        for (uint32_t side : {0u, 200u}) {
            VolumeMagnifyOptions options;
            options.weight = weight;
            options.brick_side = side;
            VolumeMagnifyStats stats;
            CHECK(magnifyVolumeValues(volume, new_size, options, stats) == want);
            CHECK(stats.bricks == 1);
            CHECK(stats.lawson.flips == expected.flips);
            CHECK(stats.lawson.cost_after == expected.cost_after);
        }
    }
}

TEST_CASE("volume magnify: the margin lets bricks flip as the whole volume does", "[volume-magnify]") {
    const std::array<uint32_t, 3> size = {14, 13, 12}, new_size = {28, 26, 24};
    const Volume volume = volumeOf(size, ball);
    VolumeMagnifyStats stats;
    const std::vector<float> whole = magnifyVolumeValues(volume, new_size, {}, stats);
    VolumeMagnifyOptions options;
    options.brick_side = 5;
    // Without a margin, the flips along the cores' sides are missing (a brick's mesh has a box
    // side there), and the results differ (measured: 32.4 dB apart).
    options.margin = 0;
    CHECK(magnifyVolumeValues(volume, new_size, options, stats) != whole);
    CHECK(stats.bricks == 27);
    // With 4 voxels of margin this ball's bricks make the whole volume's flips near every
    // voxel they resample, and the results are equal. (Not so in general: a chain of flips can
    // reach further than any margin.)
    options.margin = 4;
    CHECK(magnifyVolumeValues(volume, new_size, options, stats) == whole);
}
