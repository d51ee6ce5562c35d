// The four bistellar flips of the tetrahedral mesh (core/volume/tet_mesh.h's glossary; paper
// Sect. 4 and Fig. 6), in two steps so that a parallel rule can reuse them: plan a flip at a
// site (legality decided exactly, the gain computed from the cost cache, the tets read and
// written listed), then apply a plan.
//
// Sites: a face of a tet (2–3) and an edge of a tet (3–2, 4–4, 2–2, by the edge's ring).
// Every new tet is an old tet of the region with one vertex replaced, so its orientation comes
// from a positive record and "every new tet positive" (tetOrient > 0) is the whole legality
// test (with the exact zero orientation of the coplanar four for 4–4 and 2–2):
//   2–3  face i of t = (a, b, c) opposite d = t[i], neighbour n = (a, b, c, e):
//        new tets: t with a, b or c replaced by e.
//   3–2  interior edge (p, q) of degree 3, ring tets T_k = (p, q, r_k, r_k+1), k = 0, 1, 2:
//        new tets: T_0 with q replaced by r_2 and T_0 with p replaced by r_2. Both positive
//        iff p and q lie on opposite sides of (r_0, r_1, r_2); the ring tets being positive,
//        the line p–q already passes inside the triangle.
//   4–4  interior edge (p, q) of degree 4, ring r_0..r_3 coplanar; the new edge r_j–r_j+2
//        (j = 0 or 1, both candidates; the larger gain wins, ties r_0–r_2): new tets: the two
//        ring tets holding r_j, each with p, then q, replaced by r_j+2.
//   2–2  boundary edge (p, q) of degree 2, ring tets T_0 = (p, q, r_0, r_1), T_1 = (p, q, r_1,
//        r_2), its boundary faces (p, q, r_0) and (p, q, r_2) coplanar (thus on one side of
//        the box): new tets as for 3–2, the new edge r_0–r_2 on the box's side.
// Each plan then checks, by the faces' vertex sets, that every face of a new tet is either
// shared with another new tet or one of the region's hull faces.
//
// The gain is the cost before minus the cost after over everything whose cost changes:
//   variance  the region's tets: Σ old cost − Σ new content · variance.
//   face_scf  every face with a region tet on one side: the faces inside the region and its
//             hull faces, each scf · (content + content across) / 4 (tet_cost.h), before and
//             after; a hull face's tet across (outside the region) keeps its gradient, but
//             its face now borders a new tet, so its cost changes too.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "tet_cost.h"
#include "tet_mesh.h"

namespace ddt {

enum class FlipKind : uint8_t { two_three, three_two, four_four, two_two };
constexpr uint32_t kFlipKindCount = 4;
const char* flipKindName(FlipKind kind);  // "2-3", "3-2", "4-4", "2-2"

// A flip is worth applying when gain > kTetFlipGainThreshold · gain_scale. The 2-D rule's
// reason (glsl/image/sederberg.h, kFlipGainThreshold = 1e-12): a bare "gain > 0" flips on fp64
// rounding noise, e.g. on a linear field where every exact gain is 0, and can cycle. Here the
// costs are content-weighted and physical (a gain in mm³ of one CT, µm³ of another; face_scf
// also scales with 1 / spacing²), so an absolute threshold would mean something else for each
// volume. The threshold is therefore relative to gain_scale, the magnitude every term of the
// gain is rounded at: the region's content for variance (values in [0, 1], so content ·
// variance rounds at ≲ 1e-16 · content), Σ |∇P_a|·|∇P_b| · (content_a +
// content_b) / 4 over the faces summed for face_scf (the rounding of scf's square root and dot
// product). At most ~20 such terms round by ≲ 1e-14 of gain_scale together; measured on linear
// fields (every exact face_scf gain 0) after random flips to thin tets: ≤ 1.1e-16.
constexpr double kTetFlipGainThreshold = 1e-12;

struct FlipPlan {
    FlipKind kind = FlipKind::two_three;
    double gain = 0.0;        // total cost before − after
    double gain_scale = 0.0;  // see kTetFlipGainThreshold
    // The region: the old tets, replaced by new_tets. region[0] is the site's tet, the rest in
    // ring order (2–3: t, n). The write set: apply() rewrites these records (and, for 2–3,
    // takes one more slot; for 3–2, frees the last).
    uint32_t region_count = 0;
    std::array<uint32_t, 4> region{};
    uint32_t new_count = 0;
    std::array<TetVertices, 4> new_tets{};  // each positive
    // The hull faces: the region's faces not shared inside it, with the tet across each
    // (kNoTet on the box's side) and the entry of that tet's neighbours that points into the
    // region (apply() redirects it). The read set is the region plus these tets: the gain reads
    // their gradients (face_scf) and apply() their back-links.
    uint32_t hull_count = 0;
    std::array<uint32_t, 8> hull_outside{};
    std::array<uint8_t, 8> hull_back{};
    // links[i][f]: across face f of new tet i lies new tet links[i][f] (< 4), hull face
    // links[i][f] − 4, or, for kBoxSideLink, the box's side (a 2–2's two new boundary faces).
    std::array<std::array<uint8_t, 4>, 4> links{};
    static constexpr uint8_t kBoxSideLink = 0xfe;

    bool worthApplying() const { return gain > kTetFlipGainThreshold * gain_scale; }

    // The read set, region then hull tets (kNoTet left out), into `out`; returns its size. Two
    // plans may be applied in either order, or together, when neither's region (the write
    // set) meets the other's read set.
    uint32_t readSet(std::array<uint32_t, 12>& out) const {
        uint32_t count = 0;
        for (uint32_t k = 0; k < region_count; ++k) out[count++] = region[k];
        for (uint32_t h = 0; h < hull_count; ++h)
            if (hull_outside[h] != kNoTet) out[count++] = hull_outside[h];
        return count;
    }
};

// The 2–3 flip of face `face` of tet t: none when the face is on the box's side or the flip
// is illegal (the segment d–e does not cross the face's interior).
std::optional<FlipPlan> planTwoThree(const TetMesh& mesh, const TetCosts& costs, uint32_t t, uint32_t face);

// The flip of the edge (t[i], t[j]) by its ring: 3–2 (interior, degree 3), 4–4 (interior,
// degree 4, coplanar ring; the better diagonal), 2–2 (boundary, degree 2, coplanar boundary
// faces); none otherwise or when illegal.
std::optional<FlipPlan> planEdgeFlip(const TetMesh& mesh, const TetCosts& costs, uint32_t t, uint32_t i, uint32_t j);

// The 4–4 flip of the edge (t[i], t[j]) to one diagonal: r_0–r_2 (diagonal 0) or r_1–r_3
// (diagonal 1), r_0 = the ring vertex of t that follows p, q in t's orientation.
std::optional<FlipPlan> planFourFour(const TetMesh& mesh, const TetCosts& costs, uint32_t t, uint32_t i, uint32_t j,
                                     uint32_t diagonal);

// The flip worth applying (FlipPlan::worthApplying) with the largest gain among t's sites: its
// 4 faces (2–3), then its 6 edges (0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3); ties go to
// the first. A region whose tets are all flat is skipped before any legality test: its values
// are all equal (the tets share faces), so every gradient and variance, before and after, is
// exactly 0, and so is the gain.
std::optional<FlipPlan> bestFlipAt(const TetMesh& mesh, const TetCosts& costs, uint32_t t);

// The ring of the edge (t[i], t[j]) = (p, q): tets[k] = (p, q, ring[k], ring[k+1]) in positive
// orientation, starting at a boundary face for a boundary edge, else at t. For an interior edge
// ring[degree] = ring[0]; for a boundary edge ring has degree + 1 vertices. Walks at most
// max_degree tets; none if the ring is longer.
struct EdgeRing {
    uint32_t p = 0, q = 0;
    uint32_t degree = 0;
    bool interior = false;
    std::array<uint32_t, 8> tets{};
    std::array<uint32_t, 9> ring{};
};
std::optional<EdgeRing> edgeRingOf(const TetMesh& mesh, uint32_t t, uint32_t i, uint32_t j, uint32_t max_degree = 8);

// The slots a flip wrote: slots[k] holds plan.new_tets[k]; freed is the slot a 3–2 gave back
// (kNoTet otherwise). `changed` lists both, for TetCosts::update().
struct AppliedFlip {
    uint32_t count = 0;
    std::array<uint32_t, 4> slots{};
    uint32_t freed = kNoTet;
    uint32_t changed_count = 0;
    std::array<uint32_t, 5> changed{};
};

// Rewrites the region's records with the new tets (the region's slots in order; a 2–3's third
// tet takes the last free slot, else a new one at the end; a 3–2's last region slot is freed:
// all four vertices and neighbours kNoTet, pushed onto free_slots), links every face, and
// redirects the hull tets' back-links. The mesh must be the one the plan was made on.
AppliedFlip applyFlip(TetMesh& mesh, const FlipPlan& plan);

// applyFlip, then costs.update() over the changed slots.
AppliedFlip applyFlip(TetMesh& mesh, TetCosts& costs, const FlipPlan& plan);

}  // namespace ddt
