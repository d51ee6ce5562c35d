// Resampling the piecewise-linear function of a tetrahedral mesh (core/volume/tet_mesh.h) to a
// new grid: every output voxel takes the barycentric interpolation of the vertex values in the
// one tet that owns its sample point. The 3-D counterpart of the 2-D renderer (core/image/render.h,
// glsl/raster.h), with the same sample positions, the same exactness and the same kind of tie
// rule.
//
// Sample positions. Along an axis with n input and m output voxels, output voxel i' samples the
// input index u = (i' + 0.5) · n / m − 0.5 = ((2i' + 1) · n − m) / (2m) (core/volume/volume.h),
// clamped to [0, n − 1]: a sample beyond the outermost voxel centres takes the nearest point of
// the box of voxel centres, i.e. the border values are replicated, as image resizers do.
//
// Exact units. Per axis, every coordinate is multiplied by 2m (a different m per axis): vertex x
// becomes X = 2m · x and sample i' the integer U = clamp((2i' + 1) · n − m, 0, 2m · (n − 1))
// (glsl/raster.h's sampleCoord and vertexCoord). A positive diagonal scaling multiplies every
// orientation determinant by the positive 8 · mx · my · mz, so no sign changes, and every test
// below is exact integer arithmetic on these units.
//
// Ownership. For a positive tet (v0, v1, v2, v3) and a point p, the face function f_i(p) is the
// orientation of the tet with p in place of v_i, an affine function of p: f_i(p) = g_i · (p − a)
// for any vertex a of face i, with gradient g_i ≠ 0 (the face is a proper triangle). p lies in
// the tet's interior exactly when all four f_i(p) > 0, and Σ f_i(p) = orient(tet) for every p.
// A sample p on no face plane is owned by the tet whose interior holds it. A sample on a face, an
// edge or a vertex (a tie) is owned by the tet that holds the symbolically perturbed point
//     p_ε = p + (σx · ε, σy · ε², σz · ε³),   ε → 0⁺,
// with σ_a = +1, except −1 when p lies on the box's high side along a (U_a = 2m · (n − 1)), so
// that p_ε stays inside the box. As f_i is affine,
//     f_i(p_ε) = f_i(p) + ε · σx · gx + ε² · σy · gy + ε³ · σz · gz,
// whose sign for small ε is that of the first nonzero term of (f_i(p), σx gx, σy gy, σz gz):
// one exists since g_i ≠ 0. So the tet owns p when each of its four faces has that sign > 0.
// Proof that exactly one tet owns every sample: each f_i(p_ε) is a nonzero polynomial in ε, so
// over all tets' faces there is an ε₀ > 0 below which none vanishes and each keeps the sign
// above; fix such an ε, also small enough that p_ε lies in the box (σ points inwards along every
// axis where p is on a side, and each side has at least 2 voxels, so the box has positive
// extent). The box is the union of the closed tets (a valid mesh: checkTetMesh), so p_ε lies in
// some closed tet T; f_i(p_ε) ≠ 0 for each of T's faces, so p_ε lies in T's interior, and T owns
// p. The tets' interiors are disjoint (a tetrahedralization), so no second tet's interior holds
// p_ε: exactly one tet owns p. No tolerance enters anywhere.
//
// Weights. The barycentric weights come from the same exact face functions:
// λ_i = f_i(p) / orient(tet), the value Σ λ_i · values[v_i] in double, stored as float. A sample
// at a vertex (×1) gets weights exactly 1, 0, 0, 0, so ×1 returns the input exactly.
//
// Integer bound. Let E_a be the extent along a of a tet's vertices in these units (the samples a
// tet tests lie within its vertices' bounding box). Every entry of the 3 × 3 determinant that
// gives f_i is a coordinate difference, at most E_a along axis a; each of its six products takes
// one entry per axis, so |f_i| ≤ 6 · Ex · Ey · Ez, and so are the partial sums and the
// gradients' products (|g_x| ≤ 2 · Ey · Ez, |g_x · Δx| ≤ 2 · Ex · Ey · Ez). A tet with
// 6 · Ex · Ey · Ez < 2^62 (computed in double; the factor 2 below 2^63 covers its rounding) is
// tested in int64 (a tet w voxels wide has E_a = 2 · m_a · w: a Kuhn tet, w = 1, fits while
// mx · my · mz < 2^56, e.g. 2^18 output voxels per axis), any other in __int128. The box's
// extents D_a = 2 · m_a · (n_a − 1) bound every E_a, and checkTetResampleSize requires
// 6 · Dx · Dy · Dz < 2^126 (e.g. 2^16 input voxels magnified ×64 along every axis fits). The
// GLSL kernel (glsl/volume/tet_resample.comp), which has no 128-bit integers, tests in int64
// exactly the tets that pass this bound and defers the others to resampleTetSlotsInto on the
// host: the bound is on a tet's own extents, so bricks would not widen it.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tet_mesh.h"

namespace ddt {

// "" if a grid of `size` voxels can be resampled to `new_size` (each side at least 1) with the
// exact arithmetic above, else the reason.
std::string checkTetResampleSize(const std::array<uint32_t, 3>& size, const std::array<uint32_t, 3>& new_size);

// Which integers the exact tests use: per tet the narrowest that the bound above allows, or
// __int128 for every tet (tests compare the two: int64 suffices for every mesh small enough to
// test, so the wide path would otherwise go untested).
enum class TetArithmetic { narrowest, wide };

// The mesh's piecewise-linear function resampled to new_size voxels (x fastest): `values` holds
// one value per vertex id (physical values, core/volume/volume.h). Runs on the threads of
// core/parallel.h, over the tets (free slots skipped), each over the output voxels in its
// bounding box: ownership is exclusive, so no two tets write one voxel.
std::vector<float> resampleTets(const TetMesh& mesh, const std::vector<float>& values,
                                const std::array<uint32_t, 3>& new_size,
                                TetArithmetic arithmetic = TetArithmetic::narrowest);

// Part of a larger resampling, for a mesh of one brick of a volume (core/volume/volume_magnify.h):
// the whole grid's sizes fix every sample's position and the exact units, the brick's mesh
// sits at `vertex_offset` in the whole input, and only the output voxels of [out_begin,
// out_end) per axis are resampled. The brick's vertices' box must hold those samples, and an
// inner side of the box must not be where a sample lies (its push would leave the brick):
// bricks with a margin of at least one voxel past the samples they resample.
struct TetResampleWindow {
    std::array<uint32_t, 3> size{};      // the whole input's voxels (n per axis)
    std::array<uint32_t, 3> new_size{};  // the whole output's voxels (m per axis)
    std::array<uint32_t, 3> vertex_offset{};
    std::array<uint32_t, 3> out_begin{}, out_end{};
};

// Resamples the window's output voxels into `out` (the whole output, new_size voxels, x fastest).
void resampleTetsInto(const TetMesh& mesh, const std::vector<float>& values, const TetResampleWindow& window,
                      float* out, TetArithmetic arithmetic = TetArithmetic::narrowest);

// resampleTetsInto over the tets of `slots` only (every slot when null): the samples they own,
// and no others, are written. For a device that resamples most tets and leaves a few to core
// (compute/volume/tet_resample_device.h).
void resampleTetSlotsInto(const TetMesh& mesh, const std::vector<float>& values, const TetResampleWindow& window,
                          const std::vector<uint32_t>* slots, float* out,
                          TetArithmetic arithmetic = TetArithmetic::narrowest);

// The owner of every output sample as resampleTets decides it (tests): the owning tet's slot,
// kNoTet where no tet claims the sample, kManyTets where more than one does.
constexpr uint32_t kManyTets = 0xfffffffeu;
std::vector<uint32_t> tetSampleOwners(const TetMesh& mesh, const std::array<uint32_t, 3>& new_size,
                                      TetArithmetic arithmetic = TetArithmetic::narrowest);

}  // namespace ddt
