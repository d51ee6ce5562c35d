#include "tet_flips.h"

#include <cassert>
#include <cmath>

namespace ddt {

namespace {

// For the edge at record positions (i, j): the other two positions (c, d) such that (i, j, c, d)
// is an even permutation of (0, 1, 2, 3), so that (t[i], t[j], t[c], t[d]) keeps t's positive
// orientation. kOtherPair[i][j] = {c, d}; unused on the diagonal.
constexpr uint8_t kOtherPair[4][4][2] = {
    {{0, 0}, {2, 3}, {3, 1}, {1, 2}},
    {{3, 2}, {0, 0}, {0, 3}, {2, 0}},
    {{1, 3}, {3, 0}, {0, 0}, {0, 1}},
    {{2, 1}, {0, 2}, {1, 0}, {0, 0}},
};

uint32_t positionIn(const TetVertices& t, uint32_t v) {
    for (uint32_t k = 0; k < 4; ++k)
        if (t[k] == v) return k;
    return 4;
}

uint32_t indexIn(const uint32_t* list, uint32_t count, uint32_t value) {
    for (uint32_t k = 0; k < count; ++k)
        if (list[k] == value) return k;
    return count;
}

TetVertices replaced(const TetVertices& t, uint32_t position, uint32_t v) {
    TetVertices r = t;
    r[position] = v;
    return r;
}

// A face's term of face_scf's total, scf · (content_a + content_b) / 4, and the magnitude it
// rounds at, |g_a|·|g_b| · (content_a + content_b) / 4.
struct FaceTerm {
    double cost;
    double scale;
};
FaceTerm faceTerm(const Vec3& ga, double content_a, const Vec3& gb, double content_b) {
    const double share = (content_a + content_b) / 4.0;
    const double norms = std::sqrt((ga[0] * ga[0] + ga[1] * ga[1] + ga[2] * ga[2]) *
                                   (gb[0] * gb[0] + gb[1] * gb[1] + gb[2] * gb[2]));
    return {faceScf(ga, gb) * share, norms * share};
}

bool regionIsFlat(const TetCosts& costs, const uint32_t* region, uint32_t count) {
    for (uint32_t k = 0; k < count; ++k)
        if (!costs.flat(region[k])) return false;
    return true;
}

// Completes a plan whose kind, region and (legal) new tets are set: the hull faces, the new
// tets' links and the gain. Faces are matched by their vertex sets, as bit masks over the
// region's (at most six) vertices.
void finishPlan(const TetMesh& mesh, const TetCosts& costs, FlipPlan& plan) {
    uint32_t vertices[6];
    uint32_t vertex_count = 0;
    auto bitOf = [&](uint32_t v) {
        uint32_t k = indexIn(vertices, vertex_count, v);
        if (k == vertex_count) {
            assert(vertex_count < 6);
            vertices[vertex_count++] = v;
        }
        return uint8_t(1u << k);
    };
    auto maskOf = [&](const TetVertices& t) { return uint8_t(bitOf(t[0]) | bitOf(t[1]) | bitOf(t[2]) | bitOf(t[3])); };

    // Old faces: shared inside the region (counted once, for face_scf's before) or hull.
    uint8_t hull_mask[8];
    uint8_t hull_inner[8];  // the region index of the old tet inside each hull face
    struct InnerFace {
        uint8_t a, b;
    } inner_old[6];
    uint32_t inner_old_count = 0;
    plan.hull_count = 0;
    for (uint32_t a = 0; a < plan.region_count; ++a) {
        const uint32_t t = plan.region[a];
        const uint8_t mask = maskOf(mesh.vertices[t]);
        for (uint32_t f = 0; f < 4; ++f) {
            const uint32_t n = mesh.neighbours[t][f];
            const uint32_t b = indexIn(plan.region.data(), plan.region_count, n);
            if (b < plan.region_count) {
                if (b > a) inner_old[inner_old_count++] = {uint8_t(a), uint8_t(b)};
                continue;
            }
            assert(plan.hull_count < 8);
            const uint32_t h = plan.hull_count++;
            hull_mask[h] = uint8_t(mask & ~bitOf(mesh.vertices[t][f]));
            hull_inner[h] = uint8_t(a);
            plan.hull_outside[h] = n;
            plan.hull_back[h] = n == kNoTet ? 0 : uint8_t(indexIn(mesh.neighbours[n].data(), 4, t));
            assert(n == kNoTet || plan.hull_back[h] < 4);
        }
    }

    // New faces: shared with another new tet, else a hull face.
    uint8_t new_mask[4][4];
    for (uint32_t i = 0; i < plan.new_count; ++i) {
        const uint8_t mask = maskOf(plan.new_tets[i]);
        for (uint32_t f = 0; f < 4; ++f) new_mask[i][f] = uint8_t(mask & ~bitOf(plan.new_tets[i][f]));
    }
    for (uint32_t i = 0; i < plan.new_count; ++i)
        for (uint32_t f = 0; f < 4; ++f) {
            uint8_t link = 0xff;
            for (uint32_t j = 0; j < plan.new_count && link == 0xff; ++j)
                for (uint32_t g = 0; g < 4; ++g)
                    if (j != i && new_mask[j][g] == new_mask[i][f]) link = uint8_t(j);
            for (uint32_t h = 0; h < plan.hull_count && link == 0xff; ++h)
                if (hull_mask[h] == new_mask[i][f]) link = uint8_t(4 + h);
            // The new tets fill the region: every face matched, but for the two new boundary
            // faces of a 2–2, on the box's side.
            assert(link != 0xff || plan.kind == FlipKind::two_two);
            plan.links[i][f] = link == 0xff ? FlipPlan::kBoxSideLink : link;
        }

    if (costs.weight() == TetWeight::variance) {
        double before = 0.0, after = 0.0, content = 0.0;
        for (uint32_t a = 0; a < plan.region_count; ++a) {
            before += costs.cost(plan.region[a]);
            content += costs.content(plan.region[a]);
        }
        for (uint32_t i = 0; i < plan.new_count; ++i)
            after += costs.contentOf(plan.new_tets[i]) * costs.varianceOf(plan.new_tets[i]);
        plan.gain = before - after;
        plan.gain_scale = content;
        return;
    }

    Vec3 new_gradient[4];
    double new_content[4];
    for (uint32_t i = 0; i < plan.new_count; ++i) {
        new_gradient[i] = costs.gradientOf(plan.new_tets[i]);
        new_content[i] = costs.contentOf(plan.new_tets[i]);
    }
    double before = 0.0, after = 0.0, scale = 0.0;
    auto add = [&](double& sum, const FaceTerm& term) {
        sum += term.cost;
        scale += term.scale;
    };
    for (uint32_t k = 0; k < inner_old_count; ++k) {
        const uint32_t a = plan.region[inner_old[k].a], b = plan.region[inner_old[k].b];
        add(before, faceTerm(costs.gradient(a), costs.content(a), costs.gradient(b), costs.content(b)));
    }
    for (uint32_t h = 0; h < plan.hull_count; ++h) {
        const uint32_t o = plan.hull_outside[h];
        if (o == kNoTet) continue;
        const uint32_t a = plan.region[hull_inner[h]];
        add(before, faceTerm(costs.gradient(a), costs.content(a), costs.gradient(o), costs.content(o)));
    }
    for (uint32_t i = 0; i < plan.new_count; ++i)
        for (uint32_t f = 0; f < 4; ++f) {
            const uint32_t link = plan.links[i][f];
            if (link < 4) {
                if (link > i) add(after, faceTerm(new_gradient[i], new_content[i], new_gradient[link], new_content[link]));
                continue;
            }
            if (link == FlipPlan::kBoxSideLink) continue;
            const uint32_t o = plan.hull_outside[link - 4];
            if (o != kNoTet) add(after, faceTerm(new_gradient[i], new_content[i], costs.gradient(o), costs.content(o)));
        }
    plan.gain = before - after;
    plan.gain_scale = scale;
}

bool allPositive(const TetCosts& costs, const FlipPlan& plan) {
    for (uint32_t i = 0; i < plan.new_count; ++i)
        if (costs.orient(plan.new_tets[i]) <= 0) return false;
    return true;
}

std::optional<FlipPlan> planTwoThreeImpl(const TetMesh& mesh, const TetCosts& costs, uint32_t t, uint32_t face,
                                         bool skip_flat) {
    const uint32_t n = mesh.neighbours[t][face];
    if (n == kNoTet) return std::nullopt;
    FlipPlan plan;
    plan.kind = FlipKind::two_three;
    plan.region_count = 2;
    plan.region = {t, n, kNoTet, kNoTet};
    if (skip_flat && regionIsFlat(costs, plan.region.data(), 2)) return std::nullopt;
    const uint32_t back = indexIn(mesh.neighbours[n].data(), 4, t);
    assert(back < 4);
    const uint32_t e = mesh.vertices[n][back];
    plan.new_count = 0;
    for (uint32_t k = 0; k < 4; ++k)
        if (k != face) plan.new_tets[plan.new_count++] = replaced(mesh.vertices[t], k, e);
    if (!allPositive(costs, plan)) return std::nullopt;
    finishPlan(mesh, costs, plan);
    return plan;
}

// 3–2 and 2–2 share their new tets: T_0 with q, then p, replaced by r_2.
std::optional<FlipPlan> planRingToFace(const TetMesh& mesh, const TetCosts& costs, const EdgeRing& ring, uint32_t t,
                                       FlipKind kind, bool skip_flat) {
    FlipPlan plan;
    plan.kind = kind;
    plan.region_count = ring.degree;
    for (uint32_t k = 0; k < ring.degree; ++k) plan.region[k] = ring.tets[k];
    if (plan.region[0] != t) std::swap(plan.region[0], plan.region[1]);  // 2–2 seen from T_1
    if (skip_flat && regionIsFlat(costs, plan.region.data(), plan.region_count)) return std::nullopt;
    if (kind == FlipKind::two_two && costs.orient(ring.p, ring.q, ring.ring[0], ring.ring[2]) != 0) return std::nullopt;
    const TetVertices& t0 = mesh.vertices[ring.tets[0]];
    const uint32_t r2 = ring.ring[2];
    plan.new_count = 2;
    plan.new_tets[0] = replaced(t0, positionIn(t0, ring.q), r2);
    plan.new_tets[1] = replaced(t0, positionIn(t0, ring.p), r2);
    if (!allPositive(costs, plan)) return std::nullopt;
    finishPlan(mesh, costs, plan);
    return plan;
}

std::optional<FlipPlan> planFourFourOf(const TetMesh& mesh, const TetCosts& costs, const EdgeRing& ring,
                                       uint32_t diagonal) {
    FlipPlan plan;
    plan.kind = FlipKind::four_four;
    plan.region_count = 4;
    for (uint32_t k = 0; k < 4; ++k) plan.region[k] = ring.tets[k];
    const uint32_t j = diagonal, far = ring.ring[j + 2];
    plan.new_count = 0;
    for (uint32_t k : {j, (j + 3) % 4}) {  // the ring tets holding r_j
        const TetVertices& old = mesh.vertices[ring.tets[k]];
        plan.new_tets[plan.new_count++] = replaced(old, positionIn(old, ring.p), far);
        plan.new_tets[plan.new_count++] = replaced(old, positionIn(old, ring.q), far);
    }
    if (!allPositive(costs, plan)) return std::nullopt;
    finishPlan(mesh, costs, plan);
    return plan;
}

std::optional<FlipPlan> planEdgeImpl(const TetMesh& mesh, const TetCosts& costs, uint32_t t, uint32_t i, uint32_t j,
                                     bool skip_flat, int diagonal) {
    const std::optional<EdgeRing> ring = edgeRingOf(mesh, t, i, j, 4);
    if (!ring) return std::nullopt;
    if (ring->interior && ring->degree == 3 && diagonal < 0)
        return planRingToFace(mesh, costs, *ring, t, FlipKind::three_two, skip_flat);
    if (!ring->interior && ring->degree == 2 && diagonal < 0)
        return planRingToFace(mesh, costs, *ring, t, FlipKind::two_two, skip_flat);
    if (!ring->interior || ring->degree != 4) return std::nullopt;
    if (skip_flat && regionIsFlat(costs, ring->tets.data(), 4)) return std::nullopt;
    const auto& r = ring->ring;
    if (costs.orient(r[0], r[1], r[2], r[3]) != 0) return std::nullopt;
    if (diagonal >= 0) return planFourFourOf(mesh, costs, *ring, uint32_t(diagonal));
    std::optional<FlipPlan> first = planFourFourOf(mesh, costs, *ring, 0);
    std::optional<FlipPlan> second = planFourFourOf(mesh, costs, *ring, 1);
    if (!first) return second;
    if (second && second->gain > first->gain) return second;
    return first;
}

uint32_t takeSlot(TetMesh& mesh) {
    if (!mesh.free_slots.empty()) {
        const uint32_t slot = mesh.free_slots.back();
        mesh.free_slots.pop_back();
        return slot;
    }
    mesh.vertices.push_back({kNoTet, kNoTet, kNoTet, kNoTet});
    mesh.neighbours.push_back({kNoTet, kNoTet, kNoTet, kNoTet});
    return mesh.slotCount() - 1;
}

}  // namespace

const char* flipKindName(FlipKind kind) {
    switch (kind) {
        case FlipKind::two_three: return "2-3";
        case FlipKind::three_two: return "3-2";
        case FlipKind::four_four: return "4-4";
        case FlipKind::two_two: return "2-2";
    }
    return "?";
}

std::optional<EdgeRing> edgeRingOf(const TetMesh& mesh, uint32_t t, uint32_t i, uint32_t j, uint32_t max_degree) {
    assert(i < 4 && j < 4 && i != j && max_degree >= 1 && max_degree <= 8);
    const TetVertices& start = mesh.vertices[t];
    EdgeRing ring;
    ring.p = start[i];
    ring.q = start[j];
    // Forward from t: T_k = (p, q, x, y); the next tet lies across the face opposite x, which
    // holds p, q, y; its fourth vertex z makes (p, q, y, z) positive (it lies on the other side
    // of that face than x).
    ring.tets[0] = t;
    ring.ring[0] = start[kOtherPair[i][j][0]];
    ring.ring[1] = start[kOtherPair[i][j][1]];
    ring.degree = 1;
        uint32_t current = t;
    for (;;) {
        const TetVertices& v = mesh.vertices[current];
        const uint32_t x = ring.ring[ring.degree - 1], y = ring.ring[ring.degree];
        const uint32_t next = mesh.neighbours[current][positionIn(v, x)];
        if (next == t) {
            ring.interior = true;
            assert(ring.ring[ring.degree] == ring.ring[0]);
            return ring;
        }
        if (next == kNoTet) break;
        if (ring.degree == max_degree) return std::nullopt;
        const TetVertices& w = mesh.vertices[next];
        const uint32_t z = w[6 - positionIn(w, ring.p) - positionIn(w, ring.q) - positionIn(w, y)];
        ring.tets[ring.degree] = next;
        ring.ring[ring.degree + 1] = z;
        ++ring.degree;
        current = next;
    }
    // A boundary edge: backward from t across the face opposite y (p, q, x) to the other end;
    // there M = (p, q, w, x) is positive.
    uint32_t backward[8], backward_ring[8];
    uint32_t backward_count = 0;
    current = t;
    uint32_t x = ring.ring[0], y = ring.ring[1];
    for (;;) {
        const uint32_t previous = mesh.neighbours[current][positionIn(mesh.vertices[current], y)];
        if (previous == kNoTet) break;
        if (ring.degree + backward_count == max_degree) return std::nullopt;
        const TetVertices& m = mesh.vertices[previous];
        const uint32_t w = m[6 - positionIn(m, ring.p) - positionIn(m, ring.q) - positionIn(m, x)];
        backward[backward_count] = previous;
        backward_ring[backward_count] = w;
        ++backward_count;
        y = x;
        x = w;
        current = previous;
    }
    if (backward_count == 0) return ring;
    // Prepend the backward tets, nearest to t last.
    EdgeRing result = ring;
    result.degree = ring.degree + backward_count;
    for (uint32_t k = 0; k < backward_count; ++k) {
        result.tets[k] = backward[backward_count - 1 - k];
        result.ring[k] = backward_ring[backward_count - 1 - k];
    }
    for (uint32_t k = 0; k < ring.degree; ++k) result.tets[backward_count + k] = ring.tets[k];
    for (uint32_t k = 0; k <= ring.degree; ++k) result.ring[backward_count + k] = ring.ring[k];
    return result;
}

std::optional<FlipPlan> planTwoThree(const TetMesh& mesh, const TetCosts& costs, uint32_t t, uint32_t face) {
    assert(mesh.inUse(t) && face < 4);
    return planTwoThreeImpl(mesh, costs, t, face, false);
}

std::optional<FlipPlan> planEdgeFlip(const TetMesh& mesh, const TetCosts& costs, uint32_t t, uint32_t i, uint32_t j) {
    assert(mesh.inUse(t));
    return planEdgeImpl(mesh, costs, t, i, j, false, -1);
}

std::optional<FlipPlan> planFourFour(const TetMesh& mesh, const TetCosts& costs, uint32_t t, uint32_t i, uint32_t j,
                                     uint32_t diagonal) {
    assert(mesh.inUse(t) && diagonal < 2);
    return planEdgeImpl(mesh, costs, t, i, j, false, int(diagonal));
}

std::optional<FlipPlan> bestFlipAt(const TetMesh& mesh, const TetCosts& costs, uint32_t t) {
    assert(mesh.inUse(t));
    std::optional<FlipPlan> best;
    auto consider = [&](std::optional<FlipPlan>&& plan) {
        if (plan && plan->worthApplying() && (!best || plan->gain > best->gain)) best = std::move(plan);
    };
    for (uint32_t f = 0; f < 4; ++f) consider(planTwoThreeImpl(mesh, costs, t, f, true));
    static constexpr uint8_t kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    for (const auto& e : kEdges) consider(planEdgeImpl(mesh, costs, t, e[0], e[1], true, -1));
    return best;
}

AppliedFlip applyFlip(TetMesh& mesh, const FlipPlan& plan) {
    AppliedFlip applied;
    applied.count = plan.new_count;
    for (uint32_t k = 0; k < plan.new_count; ++k)
        applied.slots[k] = k < plan.region_count ? plan.region[k] : takeSlot(mesh);
    for (uint32_t k = 0; k < plan.new_count; ++k) mesh.vertices[applied.slots[k]] = plan.new_tets[k];
    for (uint32_t k = 0; k < plan.new_count; ++k)
        for (uint32_t f = 0; f < 4; ++f) {
            const uint32_t link = plan.links[k][f];
            if (link < 4) {
                mesh.neighbours[applied.slots[k]][f] = applied.slots[link];
                continue;
            }
            if (link == FlipPlan::kBoxSideLink) {
                mesh.neighbours[applied.slots[k]][f] = kNoTet;
                continue;
            }
            const uint32_t h = link - 4, outside = plan.hull_outside[h];
            mesh.neighbours[applied.slots[k]][f] = outside;
            if (outside != kNoTet) mesh.neighbours[outside][plan.hull_back[h]] = applied.slots[k];
        }
    for (uint32_t k = plan.new_count; k < plan.region_count; ++k) {
        const uint32_t slot = plan.region[k];
        mesh.vertices[slot] = {kNoTet, kNoTet, kNoTet, kNoTet};
        mesh.neighbours[slot] = {kNoTet, kNoTet, kNoTet, kNoTet};
        mesh.free_slots.push_back(slot);
        applied.freed = slot;
    }
    for (uint32_t k = 0; k < applied.count; ++k) applied.changed[applied.changed_count++] = applied.slots[k];
    if (applied.freed != kNoTet) applied.changed[applied.changed_count++] = applied.freed;
    return applied;
}

AppliedFlip applyFlip(TetMesh& mesh, TetCosts& costs, const FlipPlan& plan) {
    const AppliedFlip applied = applyFlip(mesh, plan);
    costs.update(mesh, applied.changed.data(), applied.changed_count);
    return applied;
}

}  // namespace ddt
