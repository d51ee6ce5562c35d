#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include "tet_test_support.h"
#include "tet_cost.h"
#include "tet_flips.h"
#include "tet_mesh.h"

using ddt::FlipKind;
using ddt::kNoTet;
using ddt::TetVertices;
using ddt::TetWeight;

using namespace ddt::test;

namespace {

uint32_t vertexId(const Size& size, uint32_t x, uint32_t y, uint32_t z) { return x + size[0] * (y + size[1] * z); }

TetVertices sorted(TetVertices t) {
    std::sort(t.begin(), t.end());
    return t;
}

// Tets as sorted vertex sets, sorted: compares meshes and plans regardless of record order.
std::vector<TetVertices> tetSets(const std::vector<TetVertices>& tets) {
    std::vector<TetVertices> sets;
    for (const TetVertices& t : tets) sets.push_back(sorted(t));
    std::sort(sets.begin(), sets.end());
    return sets;
}
std::vector<TetVertices> newTetsOf(const ddt::FlipPlan& plan) {
    return tetSets(std::vector<TetVertices>(plan.new_tets.begin(), plan.new_tets.begin() + plan.new_count));
}
std::vector<TetVertices> tetsOf(const ddt::TetMesh& mesh) {
    std::vector<TetVertices> tets;
    for (uint32_t t = 0; t < mesh.slotCount(); ++t)
        if (mesh.inUse(t)) tets.push_back(mesh.vertices[t]);
    return tetSets(tets);
}

uint32_t slotOf(const ddt::TetMesh& mesh, const TetVertices& tet) {
    for (uint32_t t = 0; t < mesh.slotCount(); ++t)
        if (mesh.inUse(t) && sorted(mesh.vertices[t]) == sorted(tet)) return t;
    FAIL("no such tet");
    return kNoTet;
}
uint32_t positionOf(const ddt::TetMesh& mesh, uint32_t t, uint32_t v) {
    const auto& record = mesh.vertices[t];
    return uint32_t(std::find(record.begin(), record.end(), v) - record.begin());
}

// A mesh from a list of tets: each made positive, neighbours linked across equal faces (the
// box's sides are left without). checkTetMesh decides whether the list tiles the box.
ddt::TetMesh meshFromTets(const Size& size, const std::vector<TetVertices>& tets) {
    ddt::TetMesh mesh;
    mesh.size = size;
    for (TetVertices t : tets) {
        if (ddt::orientOf(mesh, t) < 0) std::swap(t[2], t[3]);
        mesh.vertices.push_back(t);
    }
    linkNeighbours(mesh);
    return mesh;
}

ddt::TetCostField fieldOf(const Size& size, const std::map<uint32_t, float>& ones_and_others) {
    ddt::TetCostField field;
    field.size = size;
    field.values.assign(size_t(size[0]) * size[1] * size[2], 0.0f);
    for (const auto& [id, value] : ones_and_others) field.values[id] = value;
    return field;
}

// After a flip: a valid mesh whose cached costs equal a recomputation from scratch.
void checkAfterFlip(const ddt::TetMesh& mesh, const ddt::TetCosts& costs, const ddt::TetCostField& field) {
    CHECK(ddt::checkTetMesh(mesh) == "");
    CHECK(costs.total() == ddt::meshCost(mesh, field, costs.weight()));
}

// The unit cell (2 × 2 × 2 vertices), ids x + 2y + 4z:
//
//        011 ------- 111          6 ------- 7
//        /|          /|          /|        /|
//     001 ------- 101 |         4 ------- 5 |
//       | 010 -----|- 110       | 2 ------|- 3
//       |/         | /          |/        |/
//      000 ------- 100          0 ------- 1
constexpr uint32_t k000 = 0, k100 = 1, k010 = 2, k110 = 3, k001 = 4, k101 = 5, k011 = 6, k111 = 7;
const Size kCell = {2, 2, 2};

// The cell cut into five tets: the corners 000, 110, 101, 011 cut off, and the central tet
// (100, 010, 001, 111) of content 1/3.
ddt::TetMesh fiveTetCell() {
    return meshFromTets(kCell, {{k000, k100, k010, k001},
                                {k110, k100, k010, k111},
                                {k101, k100, k001, k111},
                                {k011, k010, k001, k111},
                                {k100, k010, k001, k111}});
}

// The five-tet cell after the 2–3 across (100, 010, 001): the corner tet at 000 and the
// central tet become three tets around the diagonal 000–111.
ddt::TetMesh fanCell() {
    return meshFromTets(kCell, {{k000, k111, k100, k010},
                                {k000, k111, k010, k001},
                                {k000, k111, k001, k100},
                                {k110, k100, k010, k111},
                                {k101, k100, k001, k111},
                                {k011, k010, k001, k111}});
}

}  // namespace

TEST_CASE("tet flips: the hand-made meshes are valid", "[tet]") {
    CHECK(ddt::checkTetMesh(fiveTetCell()) == "");
    CHECK(ddt::checkTetMesh(fanCell()) == "");
}

TEST_CASE("tet flips: a 2-3 across the cell's central face lowers the variance", "[tet]") {
    // The five-tet cell, value 1 at 100, 0 elsewhere. The face (100, 010, 001) lies between
    // the corner tet at d = 000 and the central tet, whose fourth vertex is e = 111; the
    // segment 000–111 crosses the face at its centroid (1/3, 1/3, 1/3): legal.
    //   before: corner (000 100 010 001) values {0 1 0 0}: variance 3/16, content 1/6
    //           central (100 010 001 111) {1 0 0 0}: 3/16, content 1/3    → 3/32
    //   after:  (000 111 100 010) {0 0 1 0}: 3/16 · 1/6; (000 111 010 001): 0;
    //           (000 111 001 100): 3/16 · 1/6                              → 1/16
    //   gain 3/32 − 1/16 = 1/32. The corner tets at 110 and 101 also hold 100: 2 · 3/16 · 1/6 =
    //   1/16 more in the mesh's total, before and after: 5/32 → 1/8.
    ddt::TetMesh mesh = fiveTetCell();
    const ddt::TetCostField field = fieldOf(kCell, {{k100, 1.0f}});
    ddt::TetCosts costs(mesh, field, TetWeight::variance);
    const double before = costs.total();
    CHECK(before == Approx(5.0 / 32.0).epsilon(1e-15));
    const uint32_t corner = slotOf(mesh, {k000, k100, k010, k001});
    const uint32_t central = slotOf(mesh, {k100, k010, k001, k111});
    const auto plan = ddt::planTwoThree(mesh, costs, corner, positionOf(mesh, corner, k000));
    REQUIRE(plan);
    CHECK(plan->kind == FlipKind::two_three);
    CHECK(plan->gain == Approx(1.0 / 32.0).epsilon(1e-14));
    CHECK(plan->worthApplying());
    CHECK(newTetsOf(*plan) == tetSets({{k000, k111, k100, k010}, {k000, k111, k010, k001}, {k000, k111, k001, k100}}));
    // Read and write sets: the region is the two tets; across its six hull faces lie the
    // three other corner tets and the box's sides.
    CHECK(plan->region_count == 2);
    CHECK(plan->region[0] == corner);
    CHECK(plan->region[1] == central);
    CHECK(plan->hull_count == 6);
    CHECK(std::count(plan->hull_outside.begin(), plan->hull_outside.begin() + 6, kNoTet) == 3);
    std::array<uint32_t, 12> read{};
    const uint32_t read_count = plan->readSet(read);
    std::vector<uint32_t> read_set(read.begin(), read.begin() + read_count);
    std::sort(read_set.begin(), read_set.end());
    CHECK(read_set == std::vector<uint32_t>{0, 1, 2, 3, 4});  // all five tets of the cell

    const ddt::AppliedFlip applied = ddt::applyFlip(mesh, costs, *plan);
    checkAfterFlip(mesh, costs, field);
    // No free slot: the third tet is appended.
    CHECK(applied.count == 3);
    CHECK(applied.slots == std::array<uint32_t, 4>{corner, central, 5, 0});
    CHECK(mesh.slotCount() == 6);
    CHECK(tetsOf(mesh) == tetsOf(fanCell()));
    CHECK(costs.total() == Approx(1.0 / 8.0).epsilon(1e-15));
}

TEST_CASE("tet flips: a 3-2 around the cell's diagonal lowers both weights", "[tet]") {
    // The fan cell (three tets around the diagonal 000–111, ring 100, 010, 001), value 1 at
    // 000, 0 elsewhere. The diagonal crosses the triangle (100, 010, 001): legal.
    //   variance: before, each tet around the diagonal {1 0 0 0}: 3 · 3/16 · 1/6 = 3/32;
    //             after, the corner tet {1 0 0 0} 3/16 · 1/6, the central tet 0 → 1/32.
    //             gain 1/16.
    //   face_scf: the fan tets' planes: 1 − x − y + z, 1 + x − y − z, 1 − x + y − z, each
    //             |∇|² = 3, pairwise ∇·∇ = −1: each of the 3 faces between them costs
    //             3 + 1 = 4, times (1/6 + 1/6) / 4. The other corner tets and the central tet
    //             are flat (∇ 0, scf 0 against anything). before 3 · 4/12 = 1, after 0.
    //             gain 1.
    for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
        INFO(ddt::tetWeightName(weight));
        ddt::TetMesh mesh = fanCell();
        const ddt::TetCostField field = fieldOf(kCell, {{k000, 1.0f}});
        ddt::TetCosts costs(mesh, field, weight);
        const uint32_t site = slotOf(mesh, {k000, k111, k100, k010});
        const auto ring = ddt::edgeRingOf(mesh, site, positionOf(mesh, site, k000), positionOf(mesh, site, k111));
        REQUIRE(ring);
        CHECK(ring->interior);
        CHECK(ring->degree == 3);
        const auto plan = ddt::planEdgeFlip(mesh, costs, site, positionOf(mesh, site, k000), positionOf(mesh, site, k111));
        REQUIRE(plan);
        CHECK(plan->kind == FlipKind::three_two);
        const double gain = weight == TetWeight::variance ? 1.0 / 16.0 : 1.0;
        CHECK(plan->gain == Approx(gain).epsilon(1e-14));
        CHECK(costs.total() == Approx(weight == TetWeight::variance ? 3.0 / 32.0 : 1.0).epsilon(1e-15));
        CHECK(newTetsOf(*plan) == tetSets({{k000, k100, k010, k001}, {k100, k010, k001, k111}}));
        CHECK(plan->region[0] == site);

        const ddt::AppliedFlip applied = ddt::applyFlip(mesh, costs, *plan);
        checkAfterFlip(mesh, costs, field);
        CHECK(costs.total() == Approx(weight == TetWeight::variance ? 1.0 / 32.0 : 0.0).margin(1e-15));
        // The region's last slot is given back: marked unused, listed free.
        CHECK(applied.freed == plan->region[2]);
        CHECK(mesh.free_slots == std::vector<uint32_t>{applied.freed});
        CHECK(mesh.vertices[applied.freed][0] == kNoTet);
        CHECK(mesh.tetCount() == 5);
        CHECK(tetsOf(mesh) == tetsOf(fiveTetCell()));

        // A 2–3 back takes the last free slot for its third tet.
        const uint32_t corner = slotOf(mesh, {k000, k100, k010, k001});
        const auto back = ddt::planTwoThree(mesh, costs, corner, positionOf(mesh, corner, k000));
        REQUIRE(back);
        CHECK(back->gain == Approx(-gain).epsilon(1e-14));
        CHECK_FALSE(back->worthApplying());
        const ddt::AppliedFlip again = ddt::applyFlip(mesh, costs, *back);
        CHECK(again.slots[2] == applied.freed);
        CHECK(mesh.free_slots.empty());
        CHECK(mesh.slotCount() == 6);
        checkAfterFlip(mesh, costs, field);
    }
}

TEST_CASE("tet flips: a 4-4 on a coplanar ring takes the better diagonal", "[tet]") {
    // Two Kuhn cells stacked along z (2 × 2 × 3 vertices). The face diagonal p = 001 to
    // q = 111 of the middle square is an interior edge of degree 4: from the lower cell the
    // tets walking z, x, y and z, y, x; from the upper one those walking x, y, z and y, x, z.
    // Its ring 000, 101, 112, 011 is a parallelogram in the plane z = x + y (p above, q
    // below), the degenerate case of the paper's Fig. 6: the edge p–q can become either
    // diagonal, 000–112 or 101–011. Every tet here has content 1/6.
    //
    //   values: p 1, q 0; ring 000 1, 101 1, 112 1, 011 0; all others 0.
    //   before  (p q 000 101) {1 0 1 1} 3/16   (p q 101 112) {1 0 1 1} 3/16
    //           (p q 112 011) {1 0 1 0} 4/16   (p q 011 000) {1 0 0 1} 4/16    → 14/16 · 1/6
    //   000–112 (000 112 p 101) {1 1 1 1} 0    (000 112 101 q) {1 1 1 0} 3/16
    //           (000 112 q 011) {1 1 0 0} 4/16 (000 112 011 p) {1 1 0 1} 3/16  → 10/16 · 1/6
    //   101–011 (101 011 p 000) {1 0 1 1} 3/16 (101 011 000 q) {1 0 1 0} 4/16
    //           (101 011 q 112) {1 0 0 1} 4/16 (101 011 112 p) {1 0 1 1} 3/16  → 14/16 · 1/6
    //   gains: 000–112 4/16 · 1/6 = 1/24; 101–011 0.
    const Size size = {2, 2, 3};
    const auto id = [&](uint32_t x, uint32_t y, uint32_t z) { return vertexId(size, x, y, z); };
    const uint32_t p = id(0, 0, 1), q = id(1, 1, 1);
    const uint32_t v000 = id(0, 0, 0), v101 = id(1, 0, 1), v112 = id(1, 1, 2), v011 = id(0, 1, 1);
    ddt::TetMesh mesh = ddt::kuhnTetMesh(size);
    const ddt::TetCostField field = fieldOf(size, {{p, 1.0f}, {v000, 1.0f}, {v101, 1.0f}, {v112, 1.0f}});
    ddt::TetCosts costs(mesh, field, TetWeight::variance);
    const double before = costs.total();
    const uint32_t site = slotOf(mesh, {v000, p, v101, q});
    const uint32_t i = positionOf(mesh, site, p), j = positionOf(mesh, site, q);

    const auto ring = ddt::edgeRingOf(mesh, site, i, j);
    REQUIRE(ring);
    CHECK(ring->interior);
    CHECK(ring->degree == 4);
    CHECK(costs.orient(ring->ring[0], ring->ring[1], ring->ring[2], ring->ring[3]) == 0);

    const std::vector<TetVertices> to_000_112 = tetSets({{v000, v112, p, v101}, {v000, v112, v101, q}, {v000, v112, q, v011}, {v000, v112, v011, p}});
    const std::vector<TetVertices> to_101_011 = tetSets({{v101, v011, p, v000}, {v101, v011, v000, q}, {v101, v011, q, v112}, {v101, v011, v112, p}});
    std::vector<std::vector<TetVertices>> both;
    for (uint32_t diagonal : {0u, 1u}) {
        const auto plan = ddt::planFourFour(mesh, costs, site, i, j, diagonal);
        REQUIRE(plan);
        CHECK(plan->kind == FlipKind::four_four);
        both.push_back(newTetsOf(*plan));
        CHECK(plan->gain == Approx(newTetsOf(*plan) == to_000_112 ? 1.0 / 24.0 : 0.0).margin(1e-15));
    }
    CHECK(((both[0] == to_000_112 && both[1] == to_101_011) || (both[0] == to_101_011 && both[1] == to_000_112)));

    const auto plan = ddt::planEdgeFlip(mesh, costs, site, i, j);
    REQUIRE(plan);
    CHECK(plan->kind == FlipKind::four_four);
    CHECK(newTetsOf(*plan) == to_000_112);
    CHECK(plan->gain == Approx(1.0 / 24.0).epsilon(1e-14));
    CHECK(plan->region_count == 4);
    CHECK(plan->hull_count == 8);
    ddt::applyFlip(mesh, costs, *plan);
    checkAfterFlip(mesh, costs, field);
    CHECK(mesh.tetCount() == 12);
    CHECK(mesh.free_slots.empty());
    CHECK(costs.total() == Approx(before - 1.0 / 24.0).epsilon(1e-14));
}

TEST_CASE("tet flips: a 2-2 turns a diagonal on the box's side", "[tet]") {
    // The Kuhn cell, value 1 at 000 and 110. The side z = 0 is split by the diagonal 000–110
    // into (000, 100, 110) and (000, 110, 010), coplanar boundary faces of the tets walking
    // x, y, z and y, x, z: a boundary edge of degree 2. Flipping it to 100–010:
    //   before (000 100 110 111) {1 0 1 0} 1/4; (000 010 110 111) {1 0 1 0} 1/4  → 1/2 · 1/6
    //   after  (000 100 010 111) {1 0 0 0} 3/16; (100 010 110 111) {0 0 1 0} 3/16 → 3/8 · 1/6
    //   gain 1/8 · 1/6 = 1/48.
    ddt::TetMesh mesh = ddt::kuhnTetMesh(kCell);
    const ddt::TetCostField field = fieldOf(kCell, {{k000, 1.0f}, {k110, 1.0f}});
    ddt::TetCosts costs(mesh, field, TetWeight::variance);
    const uint32_t site = slotOf(mesh, {k000, k100, k110, k111});
    const uint32_t i = positionOf(mesh, site, k000), j = positionOf(mesh, site, k110);
    const auto ring = ddt::edgeRingOf(mesh, site, i, j);
    REQUIRE(ring);
    CHECK_FALSE(ring->interior);
    CHECK(ring->degree == 2);
    const auto plan = ddt::planEdgeFlip(mesh, costs, site, i, j);
    REQUIRE(plan);
    CHECK(plan->kind == FlipKind::two_two);
    CHECK(plan->gain == Approx(1.0 / 48.0).epsilon(1e-14));
    CHECK(newTetsOf(*plan) == tetSets({{k000, k100, k010, k111}, {k100, k010, k110, k111}}));
    ddt::applyFlip(mesh, costs, *plan);
    checkAfterFlip(mesh, costs, field);  // the new faces on z = 0 have no neighbour
    CHECK(mesh.tetCount() == 6);
}

TEST_CASE("tet flips: illegal flips are refused", "[tet]") {
    const ddt::TetCostField cell_field = fieldOf(kCell, {{k000, 1.0f}, {k100, 0.5f}});

    SECTION("a 2-3 whose segment crosses the face's edge") {
        // Kuhn cell: the tets walking x, y, z and y, x, z share the face (000, 110, 111); the
        // segment 100–010 between their other vertices meets it at (1/2, 1/2, 0), on the
        // face's edge 000–110: the new tet (000, 110, 100, 010) would be flat.
        const ddt::TetMesh mesh = ddt::kuhnTetMesh(kCell);
        const ddt::TetCosts costs(mesh, cell_field, TetWeight::variance);
        const uint32_t t = slotOf(mesh, {k000, k100, k110, k111});
        CHECK_FALSE(ddt::planTwoThree(mesh, costs, t, positionOf(mesh, t, k100)));
        // Its faces on the box's sides have nothing to flip with.
        CHECK_FALSE(ddt::planTwoThree(mesh, costs, t, positionOf(mesh, t, k000)));
        CHECK_FALSE(ddt::planTwoThree(mesh, costs, t, positionOf(mesh, t, k111)));
    }
    SECTION("a 2-3 whose segment misses the face") {
        // Fan cell: (000 100 010 111) and (000 010 001 111) share the face (000, 010, 111) in
        // the plane x = z; the segment 100–001 crosses that plane at (1/2, 0, 1/2), outside
        // the face (it would need a negative weight on 010): a new tet would be negative.
        const ddt::TetMesh mesh = fanCell();
        const ddt::TetCosts costs(mesh, cell_field, TetWeight::face_scf);
        const uint32_t t = slotOf(mesh, {k000, k100, k010, k111});
        CHECK_FALSE(ddt::planTwoThree(mesh, costs, t, positionOf(mesh, t, k100)));
    }
    SECTION("edges that no flip removes") {
        const ddt::TetMesh mesh = ddt::kuhnTetMesh(kCell);
        const ddt::TetCosts costs(mesh, cell_field, TetWeight::variance);
        const uint32_t t = slotOf(mesh, {k000, k100, k110, k111});
        // The cell's diagonal: interior, degree 6.
        const auto diagonal = ddt::edgeRingOf(mesh, t, positionOf(mesh, t, k000), positionOf(mesh, t, k111));
        REQUIRE(diagonal);
        CHECK(diagonal->degree == 6);
        CHECK(diagonal->interior);
        CHECK_FALSE(ddt::planEdgeFlip(mesh, costs, t, positionOf(mesh, t, k000), positionOf(mesh, t, k111)));
        // The box's edge 000–100: degree 2, but its two boundary faces lie on z = 0 and y = 0.
        const auto box_edge = ddt::edgeRingOf(mesh, t, positionOf(mesh, t, k000), positionOf(mesh, t, k100));
        REQUIRE(box_edge);
        CHECK(box_edge->degree == 2);
        CHECK_FALSE(box_edge->interior);
        CHECK_FALSE(ddt::planEdgeFlip(mesh, costs, t, positionOf(mesh, t, k000), positionOf(mesh, t, k100)));
    }
    SECTION("a 3-2 whose edge misses the triangle") {
        // Box [0, 3] × [0, 2] × [0, 2] (4 × 3 × 3 vertices), interior vertices p = (1, 1, 1)
        // and q = (2, 1, 1). On the side x = 3, the triangle r0 = (3, 0, 0), r1 = (3, 2, 1),
        // r2 = (3, 1, 2) holds s = (3, 1, 1) inside:
        //
        //   side x = 3 (z up, y right)     z=2  .  r2  .
        //                                  z=1  .   s  r1
        //                                  z=0  r0  .  .
        //
        // The tube from p to that triangle: three tets (p, q, r_k, r_k+1) around the edge p–q
        // and three (q, s, r_k, r_k+1) around q–s. Everything else is a cone from p over the
        // box's sides: a tet (p, triangle) per triangle of the sides, each unit square split
        // along its diagonal, the side x = 3 outside the triangle in five triangles.
        // The edge p–q has degree 3, but p and q both lie before the ring's plane x = 3: the
        // segment never reaches the triangle, and the 3–2's tet (r2, q, r0, r1) would be
        // negative. The edge q–s ends on the triangle: its 3–2 tet (s, r0, r1, r2) would be flat.
        const Size size = {4, 3, 3};
        const auto id = [&](uint32_t x, uint32_t y, uint32_t z) { return vertexId(size, x, y, z); };
        const uint32_t p = id(1, 1, 1), q = id(2, 1, 1), s = id(3, 1, 1);
        const uint32_t r[3] = {id(3, 0, 0), id(3, 2, 1), id(3, 1, 2)};
        std::vector<TetVertices> tets;
        for (uint32_t k = 0; k < 3; ++k) {
            tets.push_back({p, q, r[k], r[(k + 1) % 3]});
            tets.push_back({q, s, r[k], r[(k + 1) % 3]});
        }
        for (uint32_t axis = 0; axis < 3; ++axis)
            for (uint32_t level : {0u, size[axis] - 1}) {
                if (axis == 0 && level == 3) continue;
                const uint32_t b = (axis + 1) % 3, c = (axis + 2) % 3;
                for (uint32_t u = 0; u + 1 < size[b]; ++u)
                    for (uint32_t v = 0; v + 1 < size[c]; ++v) {
                        auto at = [&](uint32_t du, uint32_t dv) {
                            std::array<uint32_t, 3> xyz;
                            xyz[axis] = level;
                            xyz[b] = u + du;
                            xyz[c] = v + dv;
                            return id(xyz[0], xyz[1], xyz[2]);
                        };
                        tets.push_back({p, at(0, 0), at(1, 0), at(1, 1)});
                        tets.push_back({p, at(0, 0), at(1, 1), at(0, 1)});
                    }
            }
        const uint32_t outer[5][3][2] = {{{0, 0}, {1, 0}, {2, 1}}, {{1, 0}, {2, 0}, {2, 1}}, {{2, 1}, {2, 2}, {1, 2}},
                                         {{0, 0}, {1, 2}, {0, 1}}, {{0, 1}, {1, 2}, {0, 2}}};  // (y, z) on x = 3
        for (const auto& triangle : outer)
            tets.push_back({p, id(3, triangle[0][0], triangle[0][1]), id(3, triangle[1][0], triangle[1][1]),
                            id(3, triangle[2][0], triangle[2][1])});
        const ddt::TetMesh mesh = meshFromTets(size, tets);
        REQUIRE(ddt::checkTetMesh(mesh) == "");
        CHECK(mesh.tetCount() == 6 + 4 * 12 + 8 + 5);

        ddt::TetCostField field;
        field.size = size;
        for (uint32_t v = 0; v < mesh.vertexCount(); ++v) field.values.push_back(float(v % 3) / 2.0f);
        const ddt::TetCosts costs(mesh, field, TetWeight::face_scf);
        for (const auto& [a, b] : {std::pair{p, q}, std::pair{q, s}}) {
            const uint32_t t = slotOf(mesh, a == p ? TetVertices{p, q, r[0], r[1]} : TetVertices{q, s, r[0], r[1]});
            const auto ring = ddt::edgeRingOf(mesh, t, positionOf(mesh, t, a), positionOf(mesh, t, b));
            REQUIRE(ring);
            CHECK(ring->interior);
            CHECK(ring->degree == 3);
            std::array<uint32_t, 3> ring_vertices = {ring->ring[0], ring->ring[1], ring->ring[2]};
            std::sort(ring_vertices.begin(), ring_vertices.end());
            std::array<uint32_t, 3> expected = {r[0], r[1], r[2]};
            std::sort(expected.begin(), expected.end());
            CHECK(ring_vertices == expected);
            CHECK_FALSE(ddt::planEdgeFlip(mesh, costs, t, positionOf(mesh, t, a), positionOf(mesh, t, b)));
        }
    }
}

TEST_CASE("tet flips: every legal flip keeps the mesh valid and its gain exact", "[tet]") {
    // Seeded: on small Kuhn meshes with stepped values and anisotropic voxels, apply legal
    // flips at random sites (uphill ones too) and compare each gain with the totals
    // recomputed from scratch before and after.
    uint32_t state = 12345;
    auto next = [&]() {
        state = state * 1664525u + 1013904223u;
        return state >> 8;
    };
    std::array<uint64_t, ddt::kFlipKindCount> applied{};
    for (uint32_t round = 0; round < 6; ++round) {
        const Size size = {2 + next() % 3, 2 + next() % 3, 2 + next() % 3};
        ddt::TetCostField field;
        field.size = size;
        field.spacing = {0.5 + next() % 3, 1.0, 0.25 * (1 + next() % 8)};
        std::vector<float> raw;
        for (uint32_t v = 0; v < size[0] * size[1] * size[2]; ++v) raw.push_back(float(next() % 4));
        field.values = ddt::normalizedValues(raw);
        for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
            INFO("round " << round << ", " << ddt::tetWeightName(weight));
            ddt::TetMesh mesh = ddt::kuhnTetMesh(size);
            ddt::TetCosts costs(mesh, field, weight);
            for (uint32_t step = 0; step < 400; ++step) {
                const uint32_t t = next() % mesh.slotCount(), site = next() % 10;
                if (!mesh.inUse(t)) continue;
                static constexpr uint32_t kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
                const auto plan = site < 4 ? ddt::planTwoThree(mesh, costs, t, site)
                                           : ddt::planEdgeFlip(mesh, costs, t, kEdges[site - 4][0], kEdges[site - 4][1]);
                if (!plan) continue;
                const double before = ddt::meshCost(mesh, field, weight);
                ddt::applyFlip(mesh, costs, *plan);
                ++applied[uint32_t(plan->kind)];
                const std::string problem = ddt::checkTetMesh(mesh);
                REQUIRE(problem == "");
                const double after = ddt::meshCost(mesh, field, weight);
                REQUIRE(costs.total() == after);
                // The totals round at ~1e-16 of each term; the gain's terms at its scale.
                REQUIRE(std::abs((before - after) - plan->gain) <= 1e-13 * (plan->gain_scale + std::abs(before)));
            }
        }
    }
    for (uint32_t kind = 0; kind < ddt::kFlipKindCount; ++kind) {
        INFO(ddt::flipKindName(FlipKind(kind)));
        CHECK(applied[kind] > 0);
    }
}
