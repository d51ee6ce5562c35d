#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "tet_test_support.h"
#include "tet_mesh.h"
#include "tet_resample.h"
#include "volume.h"

using namespace ddt::test;

namespace {

size_t voxelCount(const Size& s) { return size_t(s[0]) * s[1] * s[2]; }

// A tetrahedralization other than Kuhn's, with no shared body diagonal: each cell cut into five
// tets, the regular one on the cell's four corners of even x + y + z and one at each odd corner.
// Every cell face's diagonal joins its even corners, so faces match across cells. A free slot
// sits after every seventh tet, so the resampler must skip them.
//
//     odd corner o and its three axis neighbours (all even):   o ── e
//                                                              │ ╲
//                                                              e   e
ddt::TetMesh fiveTetMesh(const Size& size) {
    ddt::TetMesh mesh;
    mesh.size = size;
    auto id = [&](uint32_t x, uint32_t y, uint32_t z) { return x + size[0] * (y + size[1] * z); };
    auto add = [&](ddt::TetVertices t) {
        if (ddt::orientOf(mesh, t) < 0) std::swap(t[2], t[3]);
        mesh.vertices.push_back(t);
        if (mesh.vertices.size() % 8 == 7) {
            mesh.free_slots.push_back(mesh.slotCount());
            mesh.vertices.push_back({ddt::kNoTet, ddt::kNoTet, ddt::kNoTet, ddt::kNoTet});
        }
    };
    for (uint32_t z = 0; z + 1 < size[2]; ++z)
        for (uint32_t y = 0; y + 1 < size[1]; ++y)
            for (uint32_t x = 0; x + 1 < size[0]; ++x) {
                ddt::TetVertices even;
                int evens = 0;
                for (uint32_t c = 0; c < 8; ++c) {
                    const uint32_t dx = c & 1, dy = c >> 1 & 1, dz = c >> 2 & 1;
                    if ((x + dx + y + dy + z + dz) % 2 == 0) {
                        even[evens++] = id(x + dx, y + dy, z + dz);
                        continue;
                    }
                    add({id(x + dx, y + dy, z + dz), id(x + 1 - dx, y + dy, z + dz), id(x + dx, y + 1 - dy, z + dz),
                         id(x + dx, y + dy, z + 1 - dz)});
                }
                add(even);
            }
    linkNeighbours(mesh);
    return mesh;
}

// Output sample i' along an axis of n input and m output voxels, in units of 1/(2m) input voxels,
// clamped to the box of voxel centres, and its push σ (written from tet_resample.h's words).
int64_t sampleUnits(uint32_t i, uint32_t n, uint32_t m) {
    return std::clamp<int64_t>((2 * int64_t(i) + 1) * n - m, 0, 2 * int64_t(m) * (n - 1));
}
int samplePush(uint32_t i, uint32_t n, uint32_t m) { return sampleUnits(i, n, m) == 2 * int64_t(m) * (n - 1) ? -1 : 1; }

// Polynomials in ε with exact integer coefficients (degree ≤ 9: a 3 × 3 determinant of entries of
// degree ≤ 3), for the symbolic perturbation, computed here without the face functions'
// gradients that the resampler uses.
using Poly = std::array<__int128, 10>;
Poly operator-(const Poly& a, const Poly& b) {
    Poly r{};
    for (int k = 0; k < 10; ++k) r[k] = a[k] - b[k];
    return r;
}
Poly operator+(const Poly& a, const Poly& b) {
    Poly r{};
    for (int k = 0; k < 10; ++k) r[k] = a[k] + b[k];
    return r;
}
Poly operator*(const Poly& a, const Poly& b) {
    Poly r{};
    for (int i = 0; i < 10; ++i)
        for (int j = 0; i + j < 10; ++j) r[i + j] += a[i] * b[j];
    return r;
}
// The sign for infinitesimal ε > 0: that of the lowest nonzero coefficient.
int signOf(const Poly& p) {
    for (__int128 c : p)
        if (c != 0) return c > 0 ? 1 : -1;
    return 0;
}

using PolyPoint = std::array<Poly, 3>;
Poly orientPoly(const PolyPoint& a, const PolyPoint& b, const PolyPoint& c, const PolyPoint& d) {
    PolyPoint u, v, w;
    for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], v[k] = c[k] - a[k], w[k] = d[k] - a[k];
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

struct OwnerCount {
    std::vector<uint32_t> owner;   // per sample: the last tet found owning it
    std::vector<int> owners;       // per sample: how many tets own it (must be 1)
    std::vector<int> closed;       // per sample: how many closed tets contain it (ties: > 1)
};

// For every sample and every tet, slowly: whether the tet owns the sample under the perturbation
// p + (σx ε, σy ε², σz ε³), by the sign of each face's orientation as a polynomial in ε; and
// whether the closed tet contains the unperturbed sample.
OwnerCount countOwners(const ddt::TetMesh& mesh, const Size& out) {
    const Size& in = mesh.size;
    OwnerCount count;
    count.owner.assign(voxelCount(out), ddt::kNoTet);
    count.owners.assign(voxelCount(out), 0);
    count.closed.assign(voxelCount(out), 0);
    auto constant = [](int64_t c) {
        Poly p{};
        p[0] = c;
        return p;
    };
    for (uint32_t t = 0; t < mesh.slotCount(); ++t) {
        if (!mesh.inUse(t)) continue;
        std::array<PolyPoint, 4> v;
        for (int k = 0; k < 4; ++k) {
            const ddt::VertexCoordinates c = ddt::coordinatesOf(mesh, mesh.vertices[t][k]);
            v[k] = {constant(2 * int64_t(out[0]) * c.x), constant(2 * int64_t(out[1]) * c.y),
                    constant(2 * int64_t(out[2]) * c.z)};
        }
        for (uint32_t z = 0; z < out[2]; ++z)
            for (uint32_t y = 0; y < out[1]; ++y)
                for (uint32_t x = 0; x < out[0]; ++x) {
                    PolyPoint p = {constant(sampleUnits(x, in[0], out[0])), constant(sampleUnits(y, in[1], out[1])),
                                   constant(sampleUnits(z, in[2], out[2]))};
                    p[0][1] = samplePush(x, in[0], out[0]);
                    p[1][2] = samplePush(y, in[1], out[1]);
                    p[2][3] = samplePush(z, in[2], out[2]);
                    bool owns = true, contains = true;
                    for (int i = 0; i < 4; ++i) {
                        std::array<PolyPoint, 4> q = v;
                        q[i] = p;
                        const Poly f = orientPoly(q[0], q[1], q[2], q[3]);
                        owns &= signOf(f) > 0;
                        contains &= f[0] >= 0;
                    }
                    const size_t s = x + size_t(out[0]) * (y + size_t(out[1]) * z);
                    if (owns) ++count.owners[s], count.owner[s] = t;
                    count.closed[s] += contains;
                }
    }
    return count;
}

// The input index a sample lies at, clamped to the box of voxel centres (volume.h).
double clampedIndex(uint32_t i, uint32_t n, uint32_t m) { return std::clamp(ddt::inputIndexOf(i, n, m), 0.0, double(n - 1)); }

std::vector<float> randomValues(const ddt::TetMesh& mesh, std::mt19937& rng) {
    std::uniform_real_distribution<float> value(-1.0f, 1.0f);
    std::vector<float> values(mesh.vertexCount());
    for (float& v : values) v = value(rng);
    return values;
}

// Freudenthal / Kuhn interpolation at (u, v, w), computed from its definition: in the cell that
// holds the point, the fractional parts sorted descending f_a ≥ f_b ≥ f_c walk from the cell's
// corner along a, then b, then c, with weights 1 − f_a, f_a − f_b, f_b − f_c, f_c.
double kuhnInterpolation(const Size& size, const std::vector<float>& values, const std::array<double, 3>& u) {
    std::array<uint32_t, 3> corner;
    std::array<double, 3> frac;
    for (int a = 0; a < 3; ++a) {
        corner[a] = std::min(uint32_t(std::floor(u[a])), size[a] - 2);
        frac[a] = u[a] - corner[a];
    }
    std::array<int, 3> order = {0, 1, 2};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return frac[a] > frac[b]; });
    const double weights[4] = {1 - frac[order[0]], frac[order[0]] - frac[order[1]], frac[order[1]] - frac[order[2]],
                               frac[order[2]]};
    double sum = 0.0;
    std::array<uint32_t, 3> at = corner;
    for (int k = 0; k < 4; ++k) {
        if (k > 0) ++at[order[k - 1]];
        sum += weights[k] * values[at[0] + size[0] * (at[1] + size[1] * at[2])];
    }
    return sum;
}

struct Case {
    const char* name;
    Size in, out;
};

// Sizes whose samples land on vertices (×1), on the Kuhn cells' shared body diagonal (2³ → 4³:
// samples at 0.25 and 0.75 of a cell), on faces and edges (×3: thirds), off and on the box's high
// sides (odd ×5/3), and anisotropic ones.
const Case kOwnerCases[] = {
    {"2^3 x1", {2, 2, 2}, {2, 2, 2}},     {"2^3 x2", {2, 2, 2}, {4, 4, 4}},     {"2^3 x3", {2, 2, 2}, {6, 6, 6}},
    {"3^3 x1", {3, 3, 3}, {3, 3, 3}},     {"3^3 x2", {3, 3, 3}, {6, 6, 6}},     {"3^3 x3", {3, 3, 3}, {9, 9, 9}},
    {"3^3 x5/3", {3, 3, 3}, {5, 5, 5}},   {"3x4x5 -> 7x4x11", {3, 4, 5}, {7, 4, 11}},
    {"4x3x2 -> 12x3x6", {4, 3, 2}, {12, 3, 6}},
};

}  // namespace

TEST_CASE("tet resample: every sample owned by exactly one tet, by an independent count", "[tet-resample]") {
    int face_ties = 0, edge_or_vertex_ties = 0;
    for (const Case& c : kOwnerCases)
        for (const bool kuhn : {true, false}) {
            INFO(c.name << (kuhn ? " Kuhn" : " five tets per cell"));
            const ddt::TetMesh mesh = kuhn ? ddt::kuhnTetMesh(c.in) : fiveTetMesh(c.in);
            REQUIRE(ddt::checkTetMesh(mesh).empty());
            const OwnerCount count = countOwners(mesh, c.out);
            const std::vector<uint32_t> owners = ddt::tetSampleOwners(mesh, c.out);
            REQUIRE(owners.size() == voxelCount(c.out));
            for (size_t s = 0; s < owners.size(); ++s) {
                INFO("sample " << s << ", in " << count.closed[s] << " closed tets");
                REQUIRE(count.closed[s] >= 1);
                REQUIRE(count.owners[s] == 1);
                REQUIRE(owners[s] == count.owner[s]);
                face_ties += count.closed[s] == 2;
                edge_or_vertex_ties += count.closed[s] > 2;
            }
            CHECK(ddt::tetSampleOwners(mesh, c.out, ddt::TetArithmetic::wide) == owners);
        }
    // The cases do exercise the tie rule.
    CHECK(face_ties > 100);
    CHECK(edge_or_vertex_ties > 100);
}

TEST_CASE("tet resample: the Kuhn mesh's diagonal ties go to one tet", "[tet-resample]") {
    // 2³ → 4³: samples (0.25, 0.25, 0.25) and (0.75, 0.75, 0.75) lie on the body diagonal that all
    // six tets share.
    const ddt::TetMesh mesh = ddt::kuhnTetMesh({2, 2, 2});
    const OwnerCount count = countOwners(mesh, {4, 4, 4});
    for (const size_t s : {size_t(1 + 4 * (1 + 4 * 1)), size_t(2 + 4 * (2 + 4 * 2))}) {
        CHECK(count.closed[s] == 6);
        CHECK(count.owners[s] == 1);
    }
}

TEST_CASE("tet resample: owners on larger meshes, narrow and wide arithmetic", "[tet-resample]") {
    for (const bool kuhn : {true, false}) {
        const Size in = {9, 10, 11};
        const ddt::TetMesh mesh = kuhn ? ddt::kuhnTetMesh(in) : fiveTetMesh(in);
        for (const Size& out : {Size{9, 10, 11}, Size{18, 20, 22}, Size{27, 30, 33}, Size{23, 31, 17}, Size{4, 5, 6}}) {
            INFO((kuhn ? "Kuhn " : "five tets ") << out[0] << "x" << out[1] << "x" << out[2]);
            const std::vector<uint32_t> owners = ddt::tetSampleOwners(mesh, out);
            CHECK(std::count_if(owners.begin(), owners.end(), [](uint32_t t) { return t >= ddt::kManyTets; }) == 0);
            CHECK(ddt::tetSampleOwners(mesh, out, ddt::TetArithmetic::wide) == owners);
        }
    }
}

TEST_CASE("tet resample: any tetrahedralization reproduces a linear function", "[tet-resample]") {
    const Size sizes[][2] = {{{3, 4, 5}, {7, 4, 11}}, {{6, 6, 6}, {12, 12, 12}}, {{5, 7, 6}, {15, 21, 18}},
                             {{8, 5, 4}, {20, 13, 9}}, {{4, 4, 4}, {4, 4, 4}}};
    for (const auto& [in, out] : sizes)
        for (const bool kuhn : {true, false}) {
            INFO(out[0] << "x" << out[1] << "x" << out[2] << (kuhn ? " Kuhn" : " five tets"));
            const ddt::TetMesh mesh = kuhn ? ddt::kuhnTetMesh(in) : fiveTetMesh(in);
            auto linear = [](double x, double y, double z) { return 0.25 + 0.125 * x - 0.2 * y + 0.05 * z; };
            std::vector<float> values(mesh.vertexCount());
            for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
                const ddt::VertexCoordinates c = ddt::coordinatesOf(mesh, v);
                values[v] = float(linear(c.x, c.y, c.z));
            }
            for (const auto arithmetic : {ddt::TetArithmetic::narrowest, ddt::TetArithmetic::wide}) {
                const std::vector<float> result = ddt::resampleTets(mesh, values, out, arithmetic);
                REQUIRE(result.size() == voxelCount(out));
                double worst = 0.0;
                for (uint32_t z = 0; z < out[2]; ++z)
                    for (uint32_t y = 0; y < out[1]; ++y)
                        for (uint32_t x = 0; x < out[0]; ++x) {
                            const double expected = linear(clampedIndex(x, in[0], out[0]), clampedIndex(y, in[1], out[1]),
                                                           clampedIndex(z, in[2], out[2]));
                            const float got = result[x + size_t(out[0]) * (y + size_t(out[1]) * z)];
                            REQUIRE(std::isfinite(got));
                            worst = std::max(worst, std::abs(got - expected));
                        }
                // Values below 2 in magnitude: float's rounding is below 2^-23 · 2 ≈ 2.4e-7.
                CHECK(worst < 1e-6);
            }
        }
}

TEST_CASE("tet resample: on the Kuhn mesh, Freudenthal interpolation", "[tet-resample]") {
    std::mt19937 rng(20240611);
    const Size sizes[][2] = {{{3, 4, 5}, {7, 4, 11}}, {{5, 6, 7}, {10, 12, 14}}, {{5, 6, 7}, {15, 18, 21}},
                             {{6, 5, 4}, {11, 13, 17}}, {{2, 2, 2}, {9, 9, 9}}};
    for (const auto& [in, out] : sizes) {
        INFO(out[0] << "x" << out[1] << "x" << out[2]);
        const ddt::TetMesh mesh = ddt::kuhnTetMesh(in);
        const std::vector<float> values = randomValues(mesh, rng);
        const std::vector<float> result = ddt::resampleTets(mesh, values, out);
        double worst = 0.0;
        for (uint32_t z = 0; z < out[2]; ++z)
            for (uint32_t y = 0; y < out[1]; ++y)
                for (uint32_t x = 0; x < out[0]; ++x) {
                    const double expected = kuhnInterpolation(
                        in, values,
                        {clampedIndex(x, in[0], out[0]), clampedIndex(y, in[1], out[1]), clampedIndex(z, in[2], out[2])});
                    worst = std::max(worst, std::abs(result[x + size_t(out[0]) * (y + size_t(out[1]) * z)] - expected));
                }
        CHECK(worst < 1e-6);
    }
}

TEST_CASE("tet resample: x1 returns the input exactly", "[tet-resample]") {
    std::mt19937 rng(7);
    for (const Size& size : {Size{2, 2, 2}, Size{3, 4, 5}, Size{7, 6, 5}})
        for (const bool kuhn : {true, false}) {
            const ddt::TetMesh mesh = kuhn ? ddt::kuhnTetMesh(size) : fiveTetMesh(size);
            const std::vector<float> values = randomValues(mesh, rng);
            CHECK(ddt::resampleTets(mesh, values, size) == values);
        }
}

TEST_CASE("tet resample: the sizes exact arithmetic allows", "[tet-resample]") {
    CHECK(ddt::checkTetResampleSize({256, 256, 256}, {1024, 1024, 1024}).empty());
    CHECK(ddt::checkTetResampleSize({2, 2, 2}, {1, 1, 1}).empty());
    // 6 · (2 · 2^22 · (2^16 − 1))³ ≈ 2^119.6: fits; ×64 along each axis more does not.
    CHECK(ddt::checkTetResampleSize({65536, 65536, 65536}, {1u << 22, 1u << 22, 1u << 22}).empty());
    CHECK(!ddt::checkTetResampleSize({65536, 65536, 65536}, {1u << 25, 1u << 25, 1u << 25}).empty());
    CHECK(!ddt::checkTetResampleSize({1, 2, 2}, {2, 2, 2}).empty());
    CHECK(!ddt::checkTetResampleSize({2, 2, 2}, {2, 0, 2}).empty());
}
