#include "test_volumes.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <vector>

#include "parallel.h"

namespace bench {

namespace {

// A float volume of `size` voxels, unit spacing, voxel (0, 0, 0) at the origin.
ddt::Volume blankVolume(const std::array<uint32_t, 3>& size) {
    ddt::Volume volume;
    volume.size = size;
    volume.type = ddt::VoxelType::f32;
    for (int a = 0; a < 3; ++a) volume.index_to_world.m[a][a] = 1.0;
    volume.values.assign(volume.voxelCount(), 0.0f);
    return volume;
}

// The sub-samples' offsets from a voxel's centre along each axis: (s + 0.5) / S − 0.5.
double subsampleOffset(uint32_t s) { return (s + 0.5) / kSubsamples - 0.5; }

constexpr uint32_t kSubsampleCount = kSubsamples * kSubsamples * kSubsamples;

// How many of the voxel's sub-samples inside(x, y, z) holds at.
template <typename Inside>
uint32_t coveredCount(uint32_t x, uint32_t y, uint32_t z, Inside inside) {
    uint32_t count = 0;
    for (uint32_t k = 0; k < kSubsamples; ++k)
        for (uint32_t j = 0; j < kSubsamples; ++j)
            for (uint32_t i = 0; i < kSubsamples; ++i)
                count += inside(x + subsampleOffset(i), y + subsampleOffset(j), z + subsampleOffset(k));
    return count;
}

// Fills every voxel with voxel(x, y, z), in rows on the threads of core/parallel.h.
template <typename Voxel>
ddt::Volume sampleVolume(const std::array<uint32_t, 3>& size, Voxel voxel) {
    ddt::Volume volume = blankVolume(size);
    ddt::parallelFor(size_t(size[1]) * size[2], 8, [&](size_t begin, size_t end) {
        for (size_t row = begin; row < end; ++row) {
            const uint32_t y = uint32_t(row % size[1]), z = uint32_t(row / size[1]);
            for (uint32_t x = 0; x < size[0]; ++x) volume.values[volume.indexOf(x, y, z)] = float(voxel(x, y, z));
        }
    });
    return volume;
}

ddt::Volume sphere(const std::array<uint32_t, 3>& size) {
    const double radius = 0.3 * std::min({size[0], size[1], size[2]});
    const std::array<double, 3> centre = {0.5 * (size[0] - 1), 0.5 * (size[1] - 1), 0.5 * (size[2] - 1)};
    // A voxel's cube lies within √3 / 2 of its centre: farther from the sphere it is uniform.
    const double reach = std::sqrt(3.0) / 2;
    return sampleVolume(size, [&](uint32_t x, uint32_t y, uint32_t z) {
        const double d = std::hypot(x - centre[0], y - centre[1], z - centre[2]);
        if (d + reach < radius) return 1.0;
        if (d - reach > radius) return 0.0;
        return double(coveredCount(x, y, z, [&](double px, double py, double pz) {
                   return std::hypot(px - centre[0], py - centre[1], pz - centre[2]) <= radius;
               })) / kSubsampleCount;
    });
}

// The 3-D Shepp–Logan head phantom: Kak & Slaney, "Principles of Computerized Tomographic
// Imaging" (IEEE Press, 1988), p. 102, the table of the 3-D phantom's ten ellipsoids (as
// tabulated in T. Sadakane's sl3d, github.com/tsadakane/sl3d, "kak-slaney"), with the
// high-contrast intensities of H. Yu, Y. Ye, G. Wang, "Katsevich-type algorithms for variable
// radius spiral cone-beam CT", Proc. SPIE 5535 (2004), instead of Kak & Slaney's 2.0, −0.98,
// −0.02 …, whose soft-tissue contrasts of 1 % are invisible next to the skull. Values add where
// ellipsoids overlap, summed in integer tenths so that the brain's 1 − 0.8 − 0.2 is exactly 0. Coordinates: the cube [−1, 1]³ spans the volume's voxels edge to edge
// (x_normalised = (2x + 1) / n − 1), y and z up with their indices. Every ellipsoid turns only
// about z, by φ: its a semi-axis points along (cos φ, sin φ, 0), about its own centre.
struct Ellipsoid {
    double a, b, c;      // semi-axes
    double x0, y0, z0;   // centre
    double phi_degrees;  // rotation about z
    int tenths;          // intensity added inside, in tenths
};
constexpr Ellipsoid kSheppLogan[10] = {
    {0.6900, 0.920, 0.900, 0.00, 0.000, 0.000, 0, 10},     {0.6624, 0.874, 0.880, 0.00, 0.000, 0.000, 0, -8},
    {0.4100, 0.160, 0.210, -0.22, 0.000, -0.250, 108, -2}, {0.3100, 0.110, 0.220, 0.22, 0.000, -0.250, 72, -2},
    {0.2100, 0.250, 0.500, 0.00, 0.350, -0.250, 0, 2},     {0.0460, 0.046, 0.046, 0.00, 0.100, -0.250, 0, 2},
    {0.0460, 0.023, 0.020, -0.08, -0.650, -0.250, 0, 1},   {0.0460, 0.023, 0.020, 0.06, -0.650, -0.250, 90, 1},
    {0.0560, 0.040, 0.100, 0.06, -0.105, 0.625, 90, 2},    {0.0560, 0.056, 0.100, 0.00, 0.100, 0.625, 0, -2},
};

ddt::Volume sheppLogan(const std::array<uint32_t, 3>& size) {
    struct Placed {
        Ellipsoid e;
        double cos_phi, sin_phi;
        std::array<double, 3> half_box;  // the axis-aligned box around it, half extents
    };
    std::vector<Placed> placed;
    for (const Ellipsoid& e : kSheppLogan) {
        const double phi = e.phi_degrees * std::numbers::pi / 180.0, c = std::cos(phi), s = std::sin(phi);
        placed.push_back({e, c, s, {std::hypot(e.a * c, e.b * s), std::hypot(e.a * s, e.b * c), e.c}});
    }
    auto normalised = [&](int axis, double index) { return (2.0 * index + 1.0) / size[axis] - 1.0; };
    return sampleVolume(size, [&](uint32_t x, uint32_t y, uint32_t z) {
        const std::array<double, 3> centre = {normalised(0, x), normalised(1, y), normalised(2, z)};
        int tenths = 0;  // × sub-samples
        for (const Placed& p : placed) {
            // Only ellipsoids whose box meets the voxel's (half side 1 / n) are sub-sampled.
            const std::array<double, 3> at = {p.e.x0, p.e.y0, p.e.z0};
            bool near = true;
            for (int a = 0; a < 3; ++a) near &= std::abs(centre[a] - at[a]) <= p.half_box[a] + 1.0 / size[a];
            if (!near) continue;
            tenths += p.e.tenths * int(coveredCount(x, y, z, [&](double px, double py, double pz) {
                const double dx = normalised(0, px) - p.e.x0, dy = normalised(1, py) - p.e.y0;
                const double dz = normalised(2, pz) - p.e.z0;
                const double u = p.cos_phi * dx + p.sin_phi * dy, v = -p.sin_phi * dx + p.cos_phi * dy;
                return (u / p.e.a) * (u / p.e.a) + (v / p.e.b) * (v / p.e.b) + (dz / p.e.c) * (dz / p.e.c) <= 1.0;
            }));
        }
        return double(tenths) / (10.0 * kSubsampleCount);
    });
}

ddt::Volume slantedInterface(const std::array<uint32_t, 3>& size) {
    // Smooth part: 0.25 + 0.15 · sin(αx + βy) · cos(γz), one period across x and z, half a period
    // across y. Its mean over a voxel's sub-samples factors per axis:
    // sin(αx + βy) = Im(e^{iαx} · e^{iβy}), so tables of the per-axis means give it exactly.
    const double two_pi = 2.0 * std::numbers::pi;
    const std::array<double, 3> frequency = {two_pi / size[0], 0.5 * two_pi / size[1], two_pi / size[2]};
    std::array<std::vector<std::complex<double>>, 3> mean;
    for (int a = 0; a < 3; ++a)
        for (uint32_t i = 0; i < size[a]; ++i) {
            std::complex<double> sum = 0.0;
            for (uint32_t s = 0; s < kSubsamples; ++s) sum += std::polar(1.0, frequency[a] * (i + subsampleOffset(s)));
            mean[a].push_back(sum / double(kSubsamples));
        }
    // The step: +0.5 where x + 2y + 3z > c, the plane through the box's centre. It can cut a
    // voxel's cube only within (1 + 2 + 3) / 2 of the centre's value.
    const double c = 0.5 * ((size[0] - 1) + 2.0 * (size[1] - 1) + 3.0 * (size[2] - 1));
    return sampleVolume(size, [&](uint32_t x, uint32_t y, uint32_t z) {
        const double smooth = 0.25 + 0.15 * (mean[0][x] * mean[1][y]).imag() * mean[2][z].real();
        const double level = x + 2.0 * y + 3.0 * z - c;
        const double step = level > 3.0    ? 1.0
                            : level < -3.0 ? 0.0
                                           : double(coveredCount(x, y, z, [&](double px, double py, double pz) {
                                                  return px + 2.0 * py + 3.0 * pz > c;
                                              })) / kSubsampleCount;
        return smooth + 0.5 * step;
    });
}

}  // namespace

std::string testVolumeName(TestVolumeKind kind) {
    switch (kind) {
        case TestVolumeKind::sphere: return "sphere";
        case TestVolumeKind::shepp_logan: return "shepp-logan";
        case TestVolumeKind::slanted_interface: return "slanted-interface";
    }
    return "";
}

ddt::Volume makeTestVolume(TestVolumeKind kind, const std::array<uint32_t, 3>& size, double noise_sigma, uint64_t seed) {
    for ([[maybe_unused]] uint32_t side : size) assert(side >= 2);
    ddt::Volume volume = kind == TestVolumeKind::sphere        ? sphere(size)
                         : kind == TestVolumeKind::shepp_logan ? sheppLogan(size)
                                                               : slantedInterface(size);
    if (noise_sigma > 0) addGaussianNoise(volume, noise_sigma, seed);
    return volume;
}

void addGaussianNoise(ddt::Volume& volume, double sigma, uint64_t seed) {
    std::mt19937_64 rng(seed);
    // Uniform in (0, 1]: 53 random bits, never 0, so the logarithm is finite.
    auto uniform = [&] { return double((rng() >> 11) + 1) * 0x1p-53; };
    for (size_t i = 0; i < volume.values.size(); i += 2) {
        const double radius = sigma * std::sqrt(-2.0 * std::log(uniform())), angle = 2.0 * std::numbers::pi * uniform();
        volume.values[i] = float(volume.values[i] + radius * std::cos(angle));
        if (i + 1 < volume.values.size()) volume.values[i + 1] = float(volume.values[i + 1] + radius * std::sin(angle));
    }
}

ddt::Volume areaAverageVolume(const ddt::Volume& volume, uint32_t factor) {
    assert(factor >= 1);
    std::array<uint32_t, 3> size;
    for (int a = 0; a < 3; ++a) {
        assert(volume.size[a] % factor == 0);
        size[a] = volume.size[a] / factor;
    }
    ddt::Volume low = volume;
    low.size = size;
    low.index_to_world = ddt::resampledAffine(volume.index_to_world, volume.size, size);
    low.values.assign(low.voxelCount(), 0.0f);
    const double scale = 1.0 / (double(factor) * factor * factor);
    ddt::parallelFor(size_t(size[1]) * size[2], 8, [&](size_t begin, size_t end) {
        for (size_t row = begin; row < end; ++row) {
            const uint32_t y = uint32_t(row % size[1]), z = uint32_t(row / size[1]);
            for (uint32_t x = 0; x < size[0]; ++x) {
                double sum = 0.0;
                for (uint32_t k = 0; k < factor; ++k)
                    for (uint32_t j = 0; j < factor; ++j)
                        for (uint32_t i = 0; i < factor; ++i)
                            sum += volume.at(factor * x + i, factor * y + j, factor * z + k);
                low.values[low.indexOf(x, y, z)] = float(sum * scale);
            }
        }
    });
    return low;
}

}  // namespace bench
