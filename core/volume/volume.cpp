#include "volume.h"

#include <cassert>
#include <cmath>
#include <limits>

namespace ddt {

std::string volumeSizeProblem(const std::array<uint32_t, 3>& size) {
    const std::string voxels = std::to_string(size[0]) + " × " + std::to_string(size[1]) + " × " +
                               std::to_string(size[2]) + " voxels";
    for (uint32_t side : size)
        if (side < 2) return voxels + ": not a volume (every side needs at least 2 voxels)";
    for (uint32_t side : size)
        if (side > kMaxVolumeSide)
            return voxels + ": a side above " + std::to_string(kMaxVolumeSide) + " voxels, ddtup's limit";
    const uint64_t count = uint64_t(size[0]) * size[1] * size[2];
    if (count > kMaxVolumeVoxels)
        return voxels + ": more than " + std::to_string(kMaxVolumeVoxels) + " (2^31) voxels, ddtup's limit";
    return "";
}

std::array<double, 3> spacingOf(const Affine& index_to_world) {
    std::array<double, 3> spacing{};
    for (int a = 0; a < 3; ++a) {
        const auto& m = index_to_world.m;
        spacing[a] = std::sqrt(m[0][a] * m[0][a] + m[1][a] * m[1][a] + m[2][a] * m[2][a]);
    }
    return spacing;
}

std::array<uint32_t, 3> resampledSize(const std::array<uint32_t, 3>& size, const std::array<double, 3>& factors) {
    std::array<uint32_t, 3> result{};
    for (int a = 0; a < 3; ++a) {
        assert(factors[a] > 0 && std::isfinite(factors[a]));
        // Clamped, not wrapped, so that volumeSizeProblem() sees a size too large.
        const double m = std::round(factors[a] * size[a]);
        result[a] = m < 1 ? 1u : m > double(std::numeric_limits<uint32_t>::max()) ? std::numeric_limits<uint32_t>::max() : uint32_t(m);
    }
    return result;
}

Affine resampledAffine(const Affine& index_to_world, const std::array<uint32_t, 3>& size,
                       const std::array<uint32_t, 3>& new_size) {
    // Input index i = s_a · i' + t_a along each axis (the glossary): s_a = n_a / m_a,
    // t_a = 0.5 · s_a − 0.5. So world = A · (S i' + t): columns scaled by s, origin A · t.
    Affine result = index_to_world;
    for (int a = 0; a < 3; ++a) {
        assert(size[a] > 0 && new_size[a] > 0);
        const double scale = double(size[a]) / double(new_size[a]);
        const double shift = 0.5 * scale - 0.5;
        for (int r = 0; r < 3; ++r) {
            result.m[r][3] += index_to_world.m[r][a] * shift;
            result.m[r][a] = index_to_world.m[r][a] * scale;
        }
    }
    return result;
}

}  // namespace ddt
