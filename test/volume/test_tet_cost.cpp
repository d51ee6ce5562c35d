#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "tet_cost.h"
#include "tet_mesh.h"

namespace {

using Size = std::array<uint32_t, 3>;

uint32_t vertexId(const Size& size, uint32_t x, uint32_t y, uint32_t z) { return x + size[0] * (y + size[1] * z); }

// The slot holding the tet with these four vertices (in any order).
uint32_t slotOf(const ddt::TetMesh& mesh, ddt::TetVertices tet) {
    std::sort(tet.begin(), tet.end());
    for (uint32_t t = 0; t < mesh.slotCount(); ++t) {
        ddt::TetVertices v = mesh.vertices[t];
        std::sort(v.begin(), v.end());
        if (v == tet) return t;
    }
    FAIL("no such tet");
    return ddt::kNoTet;
}

// The unit cell's field with value(x, y, z) from `value`.
template <typename Value>
ddt::TetCostField cellField(Value value, std::array<double, 3> spacing = {1.0, 1.0, 1.0}) {
    const Size size = {2, 2, 2};
    ddt::TetCostField field;
    field.size = size;
    field.spacing = spacing;
    field.values.resize(8);
    for (uint32_t z = 0; z < 2; ++z)
        for (uint32_t y = 0; y < 2; ++y)
            for (uint32_t x = 0; x < 2; ++x) field.values[vertexId(size, x, y, z)] = value(x, y, z);
    return field;
}

}  // namespace

TEST_CASE("tet cost: values are normalized by the data's own range", "[tet]") {
    using Values = std::vector<double>;
    // Hounsfield units: air −1000, water 0, bone 3000 → 0, 0.25, 1.
    CHECK(ddt::normalizedValues(std::vector<float>{-1000.0f, 0.0f, 3000.0f}) == Values{0.0, 0.25, 1.0});
    // 8-bit and 16-bit data with the same shape give the same values.
    CHECK(ddt::normalizedValues(std::vector<float>{0.0f, 255.0f, 51.0f}) == Values{0.0, 1.0, 0.2});
    CHECK(ddt::normalizedValues(std::vector<float>{0.0f, 65535.0f, 13107.0f}) == Values{0.0, 1.0, 0.2});
    CHECK(ddt::normalizedValues(std::vector<double>{2.0, 4.0, 3.0}) == Values{0.0, 1.0, 0.5});
    // A flat volume has no range: all 0, so no tet has any weight.
    CHECK(ddt::normalizedValues(std::vector<float>{7.0f, 7.0f}) == Values{0.0, 0.0});
}

TEST_CASE("tet cost: a volume's field takes its spacing from the affine", "[tet]") {
    ddt::Volume volume;
    volume.size = {2, 2, 2};
    volume.values = {0, 10, 20, 30, 40, 50, 60, 80};
    // Columns of lengths 0.5, 0.5 and 2.5 (the y column rotated into −x, as in a DICOM frame).
    volume.index_to_world.m = {{{0.5, 0.0, 0.0, 1.0}, {0.0, -0.3, 0.0, 2.0}, {0.0, 0.4, 2.5, 3.0}}};
    const ddt::TetCostField field = ddt::tetCostFieldOf(volume);
    CHECK(field.size == volume.size);
    CHECK(field.spacing[0] == 0.5);
    CHECK(field.spacing[1] == Approx(0.5).epsilon(1e-15));
    CHECK(field.spacing[2] == 2.5);
    CHECK(field.values[7] == 1.0f);
    CHECK(field.values[4] == 0.5f);
}

TEST_CASE("tet cost: content and variance of one tet by hand", "[tet]") {
    // The Kuhn tet walking x, y, z: 000 → 100 → 110 → 111, values 0, 0.5, 1, 1.
    //   mean 0.625; deviations −0.625, −0.125, 0.375, 0.375; squares 25/64, 1/64, 9/64, 9/64;
    //   variance 44/64 / 4 = 11/64. Content: index volume 1/6 times sx · sy · sz.
    const Size size = {2, 2, 2};
    const ddt::TetMesh mesh = ddt::kuhnTetMesh(size);
    const uint32_t walk_xyz = slotOf(mesh, {0, 1, 3, 7});
    ddt::TetCostField field = cellField([](uint32_t x, uint32_t y, uint32_t z) {
        if (x == 1 && y == 0 && z == 0) return 0.5f;
        return x == 1 && y == 1 ? 1.0f : 0.0f;  // 110 and 111
    });
    REQUIRE(field.values[vertexId(size, 1, 0, 0)] == 0.5f);
    REQUIRE(field.values[vertexId(size, 1, 1, 0)] == 1.0f);
    REQUIRE(field.values[vertexId(size, 1, 1, 1)] == 1.0f);
    CHECK(ddt::tetVariance(field, mesh.vertices[walk_xyz]) == 11.0 / 64.0);
    CHECK(ddt::tetContent(mesh, field, mesh.vertices[walk_xyz]) == 1.0 / 6.0);
    CHECK(ddt::tetCost(mesh, field, ddt::TetWeight::variance, walk_xyz) == Approx(11.0 / 384.0).epsilon(1e-15));

    // CT-like voxels, 0.5 × 0.5 × 2.5 mm: the content is 0.625 / 6 mm³, the variance unchanged.
    field.spacing = {0.5, 0.5, 2.5};
    CHECK(ddt::tetContent(mesh, field, mesh.vertices[walk_xyz]) == Approx(0.625 / 6.0).epsilon(1e-15));
    CHECK(ddt::tetCost(mesh, field, ddt::TetWeight::variance, walk_xyz) == Approx(0.625 / 6.0 * 11.0 / 64.0).epsilon(1e-15));
    // The six tets fill the voxel cell.
    double total = 0.0;
    for (uint32_t t = 0; t < mesh.slotCount(); ++t) total += ddt::tetContent(mesh, field, mesh.vertices[t]);
    CHECK(total == Approx(0.625).epsilon(1e-15));
}

TEST_CASE("tet cost: the gradient of a linear field, in physical units", "[tet]") {
    // f = x/8 + y/4 + z/2 in the index frame (dyadic, so every step is exact). Every tet of the
    // cell has the gradient (1/8, 1/4, 1/2); with voxels of 0.5 × 2 × 4, one index step is s_a
    // long, so the physical gradient is (1/8 / 0.5, 1/4 / 2, 1/2 / 4) = (1/4, 1/8, 1/8).
    const ddt::TetMesh mesh = ddt::kuhnTetMesh({2, 2, 2});
    ddt::TetCostField field = cellField([](uint32_t x, uint32_t y, uint32_t z) { return x / 8.0f + y / 4.0f + z / 2.0f; });
    for (uint32_t t = 0; t < mesh.slotCount(); ++t) {
        INFO("tet " << t);
        CHECK(ddt::tetGradient(mesh, field, mesh.vertices[t]) == ddt::Vec3{0.125, 0.25, 0.5});
    }
    field.spacing = {0.5, 2.0, 4.0};
    for (uint32_t t = 0; t < mesh.slotCount(); ++t) {
        INFO("tet " << t);
        CHECK(ddt::tetGradient(mesh, field, mesh.vertices[t]) == ddt::Vec3{0.25, 0.125, 0.125});
    }
    // Parallel gradients do not bend: scf 0. Opposite ones: |g|² + |g|².
    CHECK(ddt::faceScf({1, 2, 2}, {2, 4, 4}) == 0.0);
    CHECK(ddt::faceScf({1, 2, 2}, {-1, -2, -2}) == 18.0);
    CHECK(ddt::faceScf({3, 0, 0}, {0, 4, 0}) == 12.0);  // perpendicular: |g1|·|g2|
}

TEST_CASE("tet cost: face_scf of one tet by hand, with a boundary face costing 0", "[tet]") {
    // The unit cell, value 1 at 100 and 010, 0 elsewhere. Around the diagonal 000–111 the
    // six Kuhn tets (named by their walk) and their linear interpolants:
    //   xyz 000 100 110 111   f = x − y   ∇ (1, −1, 0)
    //   yxz 000 010 110 111   f = y − x   ∇ (−1, 1, 0)
    //   xzy 000 100 101 111   f = x − z   ∇ (1, 0, −1)
    //   yzx 000 010 011 111   f = y − z   ∇ (0, 1, −1)
    //   zxy, zyx              f = 0       ∇ 0
    // Tet xyz's faces: opposite 100, shared with yxz: scf = √2·√2 − (−2) = 4; opposite 110,
    // shared with xzy: 2 − 1 = 1; opposite 000 (on x = 1) and 111 (on z = 0): boundary, 0.
    // w = (4 + 1 + 0 + 0) / 4 = 5/4; cost = 1/6 · 5/4 = 5/24.
    const ddt::TetMesh mesh = ddt::kuhnTetMesh({2, 2, 2});
    const auto values = [](uint32_t x, uint32_t y, uint32_t z) { return x + y == 1 && z == 0 ? 1.0f : 0.0f; };
    ddt::TetCostField field = cellField(values);
    const uint32_t xyz = slotOf(mesh, {0, 1, 3, 7});
    CHECK(ddt::tetGradient(mesh, field, mesh.vertices[xyz]) == ddt::Vec3{1, -1, 0});
    CHECK(ddt::tetCost(mesh, field, ddt::TetWeight::face_scf, xyz) == Approx(5.0 / 24.0).epsilon(1e-15));
    // The mesh's total, face by face: scf · (content + content) / 4 = scf / 12 over the six
    // faces around the diagonal: xyz|yxz 4, yxz|yzx 2 − 1 = 1, xzy|xyz 1, the rest 0 → 6/12.
    CHECK(ddt::meshCost(mesh, field, ddt::TetWeight::face_scf) == Approx(0.5).epsilon(1e-15));
    // The variance total: the four tets holding one 1 have values {0, 0, 0, 1} (3/16), the two
    // others none: 4 · 3/16 / 6 = 1/8.
    CHECK(ddt::meshCost(mesh, field, ddt::TetWeight::variance) == Approx(0.125).epsilon(1e-15));

    // Voxels 1 × 2 × 2: ∇ divides by the spacing, xyz (1, −1/2, 0), yxz (−1, 1/2, 0),
    // xzy (1, 0, −1/2), each |∇|² = 5/4. scf(xyz, yxz) = 5/4 + 5/4 = 5/2, scf(xyz, xzy) =
    // 5/4 − 1 = 1/4; w = (5/2 + 1/4) / 4 = 11/16; content 4/6; cost 11/24.
    field.spacing = {1.0, 2.0, 2.0};
    CHECK(ddt::tetGradient(mesh, field, mesh.vertices[xyz]) == ddt::Vec3{1, -0.5, 0});
    CHECK(ddt::tetCost(mesh, field, ddt::TetWeight::face_scf, xyz) == Approx(11.0 / 24.0).epsilon(1e-15));
}

TEST_CASE("tet cost: the cache equals the free functions, tet by tet", "[tet]") {
    // A 3 × 4 × 3 grid with arbitrary values and voxels: the cached costs are computed by the
    // same formulas, so they agree bit for bit, and total() is their (compensated) sum.
    const Size size = {3, 4, 3};
    const ddt::TetMesh mesh = ddt::kuhnTetMesh(size);
    ddt::TetCostField field;
    field.size = size;
    field.spacing = {0.7, 1.1, 2.9};
    std::vector<float> raw;
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) raw.push_back(float((v * 7919) % 13));
    field.values = ddt::normalizedValues(raw);
    for (ddt::TetWeight weight : {ddt::TetWeight::variance, ddt::TetWeight::face_scf}) {
        INFO(ddt::tetWeightName(weight));
        const ddt::TetCosts costs(mesh, field, weight);
        double sum = 0.0;
        for (uint32_t t = 0; t < mesh.slotCount(); ++t) {
            CHECK(costs.cost(t) == ddt::tetCost(mesh, field, weight, t));
            CHECK(costs.content(t) == ddt::tetContent(mesh, field, mesh.vertices[t]));
            sum += costs.cost(t);
        }
        CHECK(costs.total() == Approx(sum).epsilon(1e-14));
        CHECK(costs.total() == ddt::meshCost(mesh, field, weight));
    }
}

TEST_CASE("tet cost: a physical unit scales the cost as content times weight", "[tet]") {
    // Voxels twice as large: contents × 8; variance unchanged (values are normalized);
    // gradients × 1/2, so scf × 1/4. Totals: variance × 8, face_scf × 2 (powers of 2: exact).
    const Size size = {3, 3, 3};
    const ddt::TetMesh mesh = ddt::kuhnTetMesh(size);
    ddt::TetCostField field;
    field.size = size;
    field.spacing = {0.5, 0.75, 2.5};
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) field.values.push_back(float(v % 5) / 4.0f);
    ddt::TetCostField doubled = field;
    for (double& s : doubled.spacing) s *= 2.0;
    CHECK(ddt::meshCost(mesh, doubled, ddt::TetWeight::variance) == 8.0 * ddt::meshCost(mesh, field, ddt::TetWeight::variance));
    CHECK(ddt::meshCost(mesh, doubled, ddt::TetWeight::face_scf) == 2.0 * ddt::meshCost(mesh, field, ddt::TetWeight::face_scf));
}
