#include "tet_cost.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace ddt {

namespace {

using Position = std::array<int32_t, 3>;

// The one implementation of each per-tet formula, shared by the free functions and the cache,
// so that both round alike.

double contentFrom(int64_t orient, double content_scale) { return double(orient) * content_scale; }

// Σ (z_i − mean)² / 4 in record order.
double varianceFrom(const double z[4]) {
    const double mean = (z[0] + z[1] + z[2] + z[3]) / 4.0;
    double sum = 0.0;
    for (int i = 0; i < 4; ++i) {
        const double d = z[i] - mean;
        sum += d * d;
    }
    return sum / 4.0;
}

// ∇ solves e_k · ∇ = dz_k (k = 1, 2, 3): the inverse of the matrix of rows e_k has the
// columns e2×e3, e3×e1, e1×e2 over det = e1·(e2×e3) = orient, so
// ∇ = (dz1 e2×e3 + dz2 e3×e1 + dz3 e1×e2) / det. The cross products are exact integers
// (coordinates below 2^16). In the physical frame the interpolant is P(x / s), so component a
// divides by s_a.
Vec3 gradientFrom(const Position p[4], const double z[4], const std::array<double, 3>& spacing) {
    int64_t e[3][3];
    for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a) e[k][a] = int64_t(p[k + 1][a]) - p[0][a];
    auto cross = [&](int i, int j, int64_t out[3]) {
        out[0] = e[i][1] * e[j][2] - e[i][2] * e[j][1];
        out[1] = e[i][2] * e[j][0] - e[i][0] * e[j][2];
        out[2] = e[i][0] * e[j][1] - e[i][1] * e[j][0];
    };
    int64_t c23[3], c31[3], c12[3];
    cross(1, 2, c23);
    cross(2, 0, c31);
    cross(0, 1, c12);
    const int64_t det = e[0][0] * c23[0] + e[0][1] * c23[1] + e[0][2] * c23[2];
    assert(det != 0);
    const double dz1 = z[1] - z[0], dz2 = z[2] - z[0], dz3 = z[3] - z[0];
    Vec3 g;
    for (int a = 0; a < 3; ++a)
        g[a] = (dz1 * double(c23[a]) + dz2 * double(c31[a]) + dz3 * double(c12[a])) / (double(det) * spacing[a]);
    return g;
}

bool flatFrom(const double z[4]) { return z[0] == z[1] && z[0] == z[2] && z[0] == z[3]; }

// content · (Σ over the faces of scf against the tet across, 0 on a boundary face) / 4.
template <typename GradientOfSlot>
double faceScfCostFrom(double content, const Vec3& g, const TetNeighbours& neighbours, GradientOfSlot gradient_of) {
    double sum = 0.0;
    for (int f = 0; f < 4; ++f)
        if (neighbours[f] != kNoTet) sum += faceScf(g, gradient_of(neighbours[f]));
    return content * (sum / 4.0);
}

double contentScaleOf(const TetCostField& field) { return field.spacing[0] * field.spacing[1] * field.spacing[2] / 6.0; }

void gather(const TetMesh& mesh, const TetCostField& field, const TetVertices& t, Position p[4], double z[4]) {
    for (int i = 0; i < 4; ++i) {
        const VertexCoordinates c = coordinatesOf(mesh, t[i]);
        p[i] = {c.x, c.y, c.z};
        z[i] = field.values[t[i]];
    }
}

template <typename Value>
std::vector<double> normalize(const std::vector<Value>& values, double lo, double hi) {
    std::vector<double> normalized(values.size(), 0.0);
    assert(std::isfinite(lo) && std::isfinite(hi));
    if (!(hi > lo)) return normalized;
    const double range = hi - lo;
    for (size_t i = 0; i < values.size(); ++i) normalized[i] = (double(values[i]) - lo) / range;
    return normalized;
}

template <typename Value>
std::vector<double> normalize(const std::vector<Value>& values) {
    if (values.empty()) return {};
    const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    return normalize(values, double(*lo), double(*hi));
}

}  // namespace

const char* tetWeightName(TetWeight weight) { return weight == TetWeight::variance ? "variance" : "face_scf"; }

std::vector<double> normalizedValues(const std::vector<float>& values) { return normalize(values); }
std::vector<double> normalizedValues(const std::vector<double>& values) { return normalize(values); }
std::vector<double> normalizedValues(const std::vector<float>& values, double lo, double hi) {
    return normalize(values, lo, hi);
}

TetCostField tetCostFieldOf(const Volume& volume) {
    TetCostField field;
    field.size = volume.size;
    field.spacing = spacingOf(volume.index_to_world);
    field.values = normalizedValues(volume.values);
    return field;
}

double faceScf(const Vec3& g1, const Vec3& g2) {
    const double norms = std::sqrt((g1[0] * g1[0] + g1[1] * g1[1] + g1[2] * g1[2]) *
                                   (g2[0] * g2[0] + g2[1] * g2[1] + g2[2] * g2[2]));
    const double dot = g1[0] * g2[0] + g1[1] * g2[1] + g1[2] * g2[2];
    return norms - dot;
}

double tetContent(const TetMesh& mesh, const TetCostField& field, const TetVertices& t) {
    return contentFrom(orientOf(mesh, t), contentScaleOf(field));
}

double tetVariance(const TetCostField& field, const TetVertices& t) {
    const double z[4] = {field.values[t[0]], field.values[t[1]], field.values[t[2]], field.values[t[3]]};
    return varianceFrom(z);
}

Vec3 tetGradient(const TetMesh& mesh, const TetCostField& field, const TetVertices& t) {
    Position p[4];
    double z[4];
    gather(mesh, field, t, p, z);
    return gradientFrom(p, z, field.spacing);
}

double tetCost(const TetMesh& mesh, const TetCostField& field, TetWeight weight, uint32_t t) {
    assert(mesh.inUse(t));
    const double content = tetContent(mesh, field, mesh.vertices[t]);
    if (weight == TetWeight::variance) return content * tetVariance(field, mesh.vertices[t]);
    return faceScfCostFrom(content, tetGradient(mesh, field, mesh.vertices[t]), mesh.neighbours[t],
                           [&](uint32_t n) { return tetGradient(mesh, field, mesh.vertices[n]); });
}

double meshCost(const TetMesh& mesh, const TetCostField& field, TetWeight weight) {
    return TetCosts(mesh, field, weight).total();
}

TetCosts::TetCosts(const TetMesh& mesh, const TetCostField& field, TetWeight weight)
    : field_(&field), weight_(weight), content_scale_(contentScaleOf(field)) {
    assert(field.size == mesh.size && field.values.size() == mesh.vertexCount());
    positions_.resize(mesh.vertexCount());
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        const VertexCoordinates c = coordinatesOf(mesh, v);
        positions_[v] = {c.x, c.y, c.z};
    }
    const uint32_t slots = mesh.slotCount();
    content_.assign(slots, 0.0);
    cost_.assign(slots, 0.0);
    flat_.assign(slots, 1);
    if (weight_ == TetWeight::face_scf) gradient_.assign(slots, Vec3{});
    for (uint32_t t = 0; t < slots; ++t) refreshGeometry(mesh, t);
    for (uint32_t t = 0; t < slots; ++t)
        if (mesh.inUse(t)) cost_[t] = costFromCache(mesh, t);
}

int64_t TetCosts::orient(uint32_t a, uint32_t b, uint32_t c, uint32_t d) const {
    const Position &pa = positions_[a], &pb = positions_[b], &pc = positions_[c], &pd = positions_[d];
    return tetOrient(pa[0], pa[1], pa[2], pb[0], pb[1], pb[2], pc[0], pc[1], pc[2], pd[0], pd[1], pd[2]);
}

double TetCosts::contentOf(const TetVertices& t) const { return contentFrom(orient(t), content_scale_); }

Vec3 TetCosts::gradientOf(const TetVertices& t) const {
    const Position p[4] = {positions_[t[0]], positions_[t[1]], positions_[t[2]], positions_[t[3]]};
    const double z[4] = {value(t[0]), value(t[1]), value(t[2]), value(t[3])};
    return gradientFrom(p, z, field_->spacing);
}

double TetCosts::varianceOf(const TetVertices& t) const { return tetVariance(*field_, t); }

void TetCosts::refreshGeometry(const TetMesh& mesh, uint32_t t) {
    if (!mesh.inUse(t)) {
        content_[t] = 0.0;
        cost_[t] = 0.0;
        flat_[t] = 1;
        if (!gradient_.empty()) gradient_[t] = Vec3{};
        return;
    }
    const TetVertices& v = mesh.vertices[t];
    const double z[4] = {value(v[0]), value(v[1]), value(v[2]), value(v[3])};
    content_[t] = contentOf(v);
    flat_[t] = flatFrom(z);
    if (!gradient_.empty()) gradient_[t] = gradientOf(v);
}

double TetCosts::costFromCache(const TetMesh& mesh, uint32_t t) const {
    if (weight_ == TetWeight::variance) return content_[t] * varianceOf(mesh.vertices[t]);
    return faceScfCostFrom(content_[t], gradient_[t], mesh.neighbours[t], [&](uint32_t n) -> const Vec3& { return gradient_[n]; });
}

double TetCosts::total() const {
    // Neumaier's compensated sum: `compensation` collects the low-order bits each addition
    // rounds away.
    double sum = 0.0, compensation = 0.0;
    for (size_t t = 0; t < cost_.size(); ++t) {
        const double c = cost_[t];
        const double next = sum + c;
        compensation += std::abs(sum) >= std::abs(c) ? (sum - next) + c : (c - next) + sum;
        sum = next;
    }
    return sum + compensation;
}

void TetCosts::update(const TetMesh& mesh, const uint32_t* changed, uint32_t count) {
    const uint32_t slots = mesh.slotCount();
    if (content_.size() < slots) {
        content_.resize(slots, 0.0);
        cost_.resize(slots, 0.0);
        flat_.resize(slots, 1);
        if (!gradient_.empty()) gradient_.resize(slots, Vec3{});
    }
    for (uint32_t k = 0; k < count; ++k) refreshGeometry(mesh, changed[k]);
    for (uint32_t k = 0; k < count; ++k) {
        const uint32_t t = changed[k];
        if (!mesh.inUse(t)) continue;
        cost_[t] = costFromCache(mesh, t);
        if (weight_ != TetWeight::face_scf) continue;
        for (uint32_t n : mesh.neighbours[t])
            if (n != kNoTet) cost_[n] = costFromCache(mesh, n);
    }
}

}  // namespace ddt
