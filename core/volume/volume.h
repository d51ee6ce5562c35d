// A scalar volume (CT, MR, a simulation field): samples on a regular 3-D grid and the affine
// that places the grid in the world (physical, usually millimetre) frame.
//
// Glossary (the volume code uses these words only in these senses):
// - voxel (x, y, z): index coordinates, x fastest in memory; its sample sits at the voxel
//   centre, the integer point (x, y, z) of the index frame.
// - index_to_world: world = A · (x, y, z, 1). Column a of A's 3 × 3 part is the step of one
//   voxel along axis a in the world: its length is the spacing along a (anisotropic voxels, e.g.
//   0.5 × 0.5 × 2.5 mm CT, are the norm), its direction the axis' direction.
// - physical frame: the index frame scaled by the spacings, (x sx, y sy, z sz). Contents
//   (volumes of tetrahedra) and gradients are measured there; the axes' directions (a rotation,
//   when they are orthogonal) change neither, so the optimizer works in this frame.
// - resampling by factors (fx, fy, fz): the output has round(f_a · n_a) voxels along a, and
//   voxel centres sample the same box as the input's: output voxel i' lies at input index
//   (i' + 0.5) · n / m − 0.5 (n input voxels, m output voxels along that axis).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace ddt {

// The stored sample type of a volume file, kept for the output unless --depth says otherwise.
enum class VoxelType { u8, i8, u16, i16, f32, f64 };

// The largest volume read or written. 2^31 voxels are 8 GiB of float values before the
// tetrahedral mesh (several times that) is built, and keep every voxel and vertex id, with
// room to spare, in the uint32_t the mesh and the kernels index by. A side above 65 536
// voxels with the others at least 2 would be a sliver, not a scan; NIfTI-1 holds at most
// 32 767 (larger volumes are written as NIfTI-2).
constexpr uint32_t kMaxVolumeSide = 65536;
constexpr uint64_t kMaxVolumeVoxels = uint64_t(1) << 31;

// "" if a volume of `size` voxels can be read or written, else the reason ("512 × 512 × 1
// voxels: not a volume (every side needs at least 2 voxels)", or which limit it passes).
// Every side needs 2 voxels: a single plane has no tetrahedra.
std::string volumeSizeProblem(const std::array<uint32_t, 3>& size);

// world = m · (x, y, z, 1): m[row][column], column 3 the world position of voxel (0, 0, 0).
struct Affine {
    std::array<std::array<double, 4>, 3> m{};
    bool operator==(const Affine&) const = default;
};

// What the input file carried beyond samples and the affine (its format, both NIfTI
// affines, NRRD's space, kinds, units, key/value pairs…), for the writer to keep. Defined in
// core/io/volume_file.h; opaque here, so that core needs no file I/O.
struct VolumeMetadata;

struct Volume {
    std::array<uint32_t, 3> size{};  // voxels along x, y, z
    // The physical values (a NIfTI file's scl_slope and scl_inter applied), x fastest.
    std::vector<float> values;
    VoxelType type = VoxelType::f32;
    Affine index_to_world;
    std::shared_ptr<const VolumeMetadata> metadata;  // null for volumes made in memory

    size_t voxelCount() const { return size_t(size[0]) * size[1] * size[2]; }
    size_t indexOf(uint32_t x, uint32_t y, uint32_t z) const {
        return x + size_t(size[0]) * (y + size_t(size[1]) * z);
    }
    float at(uint32_t x, uint32_t y, uint32_t z) const { return values[indexOf(x, y, z)]; }
};

// The spacing along each axis: the lengths of index_to_world's first three columns.
std::array<double, 3> spacingOf(const Affine& index_to_world);

// The output size for factors f: round(f_a · n_a) voxels along each axis (at least 1).
std::array<uint32_t, 3> resampledSize(const std::array<uint32_t, 3>& size,
                                      const std::array<double, 3>& factors);

// The affine of a volume resampled from `size` to `new_size` voxels (see the glossary): each
// column a scaled by n_a / m_a, the origin moved to where output voxel (0, 0, 0) lies, half a
// new voxel minus half an old one along each axis. Applies to any index-to-world affine (an
// NRRD's space directions and origin, a NIfTI's qform and sform alike).
Affine resampledAffine(const Affine& index_to_world, const std::array<uint32_t, 3>& size,
                       const std::array<uint32_t, 3>& new_size);

// Where output voxel i' lies in the input's index frame along one axis: (i' + 0.5) n / m − 0.5.
inline double inputIndexOf(uint32_t output_index, uint32_t n, uint32_t m) {
    return (output_index + 0.5) * double(n) / double(m) - 0.5;
}

}  // namespace ddt
