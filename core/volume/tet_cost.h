// The cost the volume optimizer lowers by flips: the weighted content of Tóth et al.,
// "N-dimensional data-dependent reconstruction using topological changes", Sect. 3
// (../shared/papers/ndim-ddt-topological-changes.md):
//
//   cost(mesh) = Σ over tets t of content(t) · w(t)
//
// - content(t): the tet's volume in the physical frame (core/volume/volume.h), orient / 6 ·
//   sx · sy · sz with orient the exact index-frame determinant. The box's content never
//   changes, so the sum compares meshes with different numbers of tets.
// - values: the volume's samples normalized to [0, 1] by the data's own range, (v − lo) /
//   (hi − lo) with (lo, hi) = (min, max); a flat volume is all 0 (no weight, no flip). So a
//   threshold means the same for 8-bit, 16-bit and Hounsfield data.
// - w(t), one of two weights:
//   variance  the population variance of t's four vertex values (paper Sect. 3).
//   face_scf  Sederberg's cost generalized to faces (paper Sect. 3): a face f shared by t and
//             n costs scf(f) = |∇P_t|·|∇P_n| − ∇P_t·∇P_n, ∇P the gradient of the linear
//             interpolant on a tet in the physical frame; w(t) = (Σ over t's 4 faces scf) / 4.
//             A boundary face (one tet, on the box's sides) costs 0: it has no second plane
//             to bend against, and the box's sides are planes that no flip moves (the 2-D
//             cost treats boundary edges the same way, core/image/cost.h).
//   Since w(t) averages face costs, face_scf's total is also Σ over interior faces f of
//   scf(f) · (content(t) + content(n)) / 4, the form the flips' gains use (tet_flips.h).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tet_mesh.h"
#include "volume.h"

namespace ddt {

enum class TetWeight : uint8_t { variance, face_scf };

const char* tetWeightName(TetWeight weight);  // "variance", "face_scf"

// What the cost looks at: the grid, the physical voxel size and the normalized values.
struct TetCostField {
    std::array<uint32_t, 3> size{};              // vertices along x, y, z (the mesh's size)
    std::array<double, 3> spacing{1.0, 1.0, 1.0};  // physical voxel size along x, y, z
    std::vector<double> values;                  // per vertex id, in [0, 1]
};

// (v − lo) / (hi − lo) with (lo, hi) the values' (min, max); all 0 when the values are flat.
// Values must be finite. Kept in double: stored as float, a linear ramp is linear only to
// ~1e-7, which on thin tets bends the planes by more than the flips' threshold (measured on
// linear fields after random flips: face_scf gains up to 3e-12 of their scale with float
// values, at most 1.1e-16 with double).
std::vector<double> normalizedValues(const std::vector<float>& values);
std::vector<double> normalizedValues(const std::vector<double>& values);
// The same with a given range (a brick of a volume normalized by the whole volume's range).
std::vector<double> normalizedValues(const std::vector<float>& values, double lo, double hi);

// The field of a volume: its size, spacingOf(index_to_world) and its normalized values.
TetCostField tetCostFieldOf(const Volume& volume);

using Vec3 = std::array<double, 3>;

// content(t) = orient(t) / 6 · sx · sy · sz (positive for a tet of the mesh).
double tetContent(const TetMesh& mesh, const TetCostField& field, const TetVertices& t);
// Population variance of the four vertex values: Σ (z_i − mean)² / 4.
double tetVariance(const TetCostField& field, const TetVertices& t);
// ∇P of the linear interpolant on t in the physical frame. In the index frame, with edges
// e_k = p_k − p_0 and dz_k = z_k − z_0, ∇ = (dz1 e2×e3 + dz2 e3×e1 + dz3 e1×e2) / orient;
// physical component a is index component a / s_a.
Vec3 tetGradient(const TetMesh& mesh, const TetCostField& field, const TetVertices& t);
// scf = |g1|·|g2| − g1·g2, evaluated as sqrt(|g1|²·|g2|²) − g1·g2; symmetric bit for bit.
double faceScf(const Vec3& g1, const Vec3& g2);

// content(t) · w(t) of the tet in slot t (for face_scf, its faces' neighbours are read).
double tetCost(const TetMesh& mesh, const TetCostField& field, TetWeight weight, uint32_t t);

// The total cost from scratch: TetCosts(mesh, field, weight).total().
double meshCost(const TetMesh& mesh, const TetCostField& field, TetWeight weight);

// Per-slot cache of what the flips' gains read, kept up to date by update() after each flip:
// contents, gradients (face_scf only), costs, whether a tet is flat (its four values equal)
// and every vertex's coordinates (decoding an id takes divisions). A cost is computed by the
// same code from the same records whether cached at construction or refreshed by update(),
// so total() after any flips equals a fresh TetCosts' total() bit for bit.
class TetCosts {
public:
    // `field` must outlive this object.
    TetCosts(const TetMesh& mesh, const TetCostField& field, TetWeight weight);

    const TetCostField& field() const { return *field_; }
    TetWeight weight() const { return weight_; }
    const std::array<int32_t, 3>& position(uint32_t v) const { return positions_[v]; }
    double value(uint32_t v) const { return field_->values[v]; }
    double content(uint32_t t) const { return content_[t]; }
    const Vec3& gradient(uint32_t t) const { return gradient_[t]; }  // face_scf only
    double cost(uint32_t t) const { return cost_[t]; }
    bool flat(uint32_t t) const { return flat_[t] != 0; }

    // Six times the signed index-frame volume, exactly (tetOrient on cached positions).
    int64_t orient(uint32_t a, uint32_t b, uint32_t c, uint32_t d) const;
    int64_t orient(const TetVertices& t) const { return orient(t[0], t[1], t[2], t[3]); }
    // content, gradient, variance of a tet that need not be in the mesh (a flip's new tets).
    double contentOf(const TetVertices& t) const;
    Vec3 gradientOf(const TetVertices& t) const;
    double varianceOf(const TetVertices& t) const;

    // Σ cost over the slots in use, in slot order, compensated (Neumaier) so that the
    // rounding stays near one ulp of the total even for 12 M tets.
    double total() const;

    // After a flip: `changed` lists the slots it rewrote or freed (and any it appended). Their
    // data are recomputed and, for face_scf, so are the costs of their face-neighbours, whose
    // faces now border other tets.
    void update(const TetMesh& mesh, const uint32_t* changed, uint32_t count);

private:
    void refreshGeometry(const TetMesh& mesh, uint32_t t);
    double costFromCache(const TetMesh& mesh, uint32_t t) const;

    const TetCostField* field_;
    TetWeight weight_;
    double content_scale_;  // sx · sy · sz / 6
    std::vector<std::array<int32_t, 3>> positions_;  // per vertex
    std::vector<double> content_;                     // per slot
    std::vector<Vec3> gradient_;                      // per slot; empty for variance
    std::vector<double> cost_;                        // per slot; 0 for a free slot
    std::vector<uint8_t> flat_;                       // per slot
};

}  // namespace ddt
