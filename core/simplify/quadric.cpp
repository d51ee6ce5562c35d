#include "quadric.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace ddt {

namespace {

double dot(const double* u, const double* v, uint32_t n) {
    double sum = 0.0;
    for (uint32_t k = 0; k < n; ++k) sum += u[k] * v[k];
    return sum;
}

}  // namespace

Quadric& Quadric::operator+=(const Quadric& other) {
    for (uint32_t k = 0; k < std::size(a); ++k) a[k] += other.a[k];
    for (uint32_t k = 0; k < kMaxQuadricDimensions; ++k) b[k] += other.b[k];
    c += other.c;
    area += other.area;
    return *this;
}

double Quadric::at(const double* v, uint32_t n) const { return quadricValue(a, b, c, v, n); }

bool Quadric::minimiseFree(double* v, uint32_t free, uint32_t n) const {
    // ∂Q/∂v_i = 2 (Σ_j A_ij v_j + b_i) = 0 for the free i: Gaussian elimination with partial
    // pivoting on the free block (at most six unknowns).
    uint32_t index[kMaxQuadricDimensions], m = 0;
    for (uint32_t k = 0; k < n; ++k)
        if (free >> k & 1) index[m++] = k;
    auto entry = [&](uint32_t i, uint32_t j) { return a[i <= j ? quadricIndex(i, j) : quadricIndex(j, i)]; };
    double system[kMaxQuadricDimensions][kMaxQuadricDimensions + 1];
    for (uint32_t i = 0; i < m; ++i) {
        double rhs = -b[index[i]];
        for (uint32_t k = 0; k < n; ++k)
            if (!(free >> k & 1)) rhs -= entry(index[i], k) * v[k];
        for (uint32_t j = 0; j < m; ++j) system[i][j] = entry(index[i], index[j]);
        system[i][m] = rhs;
    }
    for (uint32_t col = 0; col < m; ++col) {
        uint32_t pivot = col;
        for (uint32_t r = col + 1; r < m; ++r)
            if (std::abs(system[r][col]) > std::abs(system[pivot][col])) pivot = r;
        if (std::abs(system[pivot][col]) < 1e-12) return false;
        std::swap(system[col], system[pivot]);
        for (uint32_t r = col + 1; r < m; ++r) {
            const double factor = system[r][col] / system[col][col];
            for (uint32_t j = col; j <= m; ++j) system[r][j] -= factor * system[col][j];
        }
    }
    double solution[kMaxQuadricDimensions];
    for (uint32_t i = m; i-- > 0;) {
        double sum = system[i][m];
        for (uint32_t j = i + 1; j < m; ++j) sum -= system[i][j] * solution[j];
        solution[i] = sum / system[i][i];
    }
    for (uint32_t i = 0; i < m; ++i) v[index[i]] = solution[i];
    return true;
}

Quadric planeQuadric(const double* p, const double* q, const double* r, uint32_t n, double area) {
    // An orthonormal basis e1, e2 of the plane (Gram–Schmidt); then the squared distance of v
    // is |v − p|² − ((v − p)·e1)² − ((v − p)·e2)²: A = I − e1e1ᵀ − e2e2ᵀ, b = −A p, c = pᵀA p.
    double e1[kMaxQuadricDimensions], e2[kMaxQuadricDimensions];
    for (uint32_t k = 0; k < n; ++k) {
        e1[k] = q[k] - p[k];
        e2[k] = r[k] - p[k];
    }
    const double length1 = std::sqrt(dot(e1, e1, n));
    Quadric quadric;
    if (length1 == 0.0) return quadric;
    for (uint32_t k = 0; k < n; ++k) e1[k] /= length1;
    const double along = dot(e1, e2, n);
    for (uint32_t k = 0; k < n; ++k) e2[k] -= along * e1[k];
    const double length2 = std::sqrt(dot(e2, e2, n));
    if (length2 == 0.0) return quadric;
    for (uint32_t k = 0; k < n; ++k) e2[k] /= length2;
    double ap[kMaxQuadricDimensions] = {};  // A p
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; j < n; ++j) {
            const double aij = (i == j ? 1.0 : 0.0) - e1[i] * e1[j] - e2[i] * e2[j];
            if (i <= j) quadric.a[quadricIndex(i, j)] = area * aij;
            ap[i] += aij * p[j];
        }
    for (uint32_t i = 0; i < n; ++i) quadric.b[i] = -area * ap[i];
    quadric.c = area * dot(p, ap, n);
    quadric.area = area;
    return quadric;
}

}  // namespace ddt
