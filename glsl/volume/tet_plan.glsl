// The flips' plans of core/volume/tet_flips.cpp over the kernels' arrays: edge rings, legality,
// hull faces, the new tets' links and the gain, with the gain's sums in core's order in fp64
// (`precise`), so that a plan's gain equals core's bit for bit; and bestOwnedFlipAt of
// core/volume/tet_parallel.cpp. Sites are coded as tet_layout.h's kTetSite….
//
// Written for llvmpipe, which runs 8 invocations in the lanes of one SIMD register: a loop
// whose trip count is data-dependent, or an array indexed by data, costs a scalar load or store
// per lane and a mask test per step. So every small loop here has a constant trip count and is
// unrolled ([[unroll]]), arrays are indexed by constants, and a data-dependent choice among a
// few values is a chain of selects. The ring and the plan being built are this invocation's
// globals rather than values passed around, which llvmpipe copied (arrays and all) at every
// call. What differs from core's code is only how the same faces are found: core matches faces
// by bit masks of their vertices and numbers the hull faces as it meets them; here a face is
// its sorted vertex triple and a hull face keeps the number 4 · a + f of the region tet a and
// face f it lies on (core's order of hull faces is that order, so every sum runs in core's
// order).
#extension GL_EXT_control_flow_attributes : require

#include "tet_common.glsl"

const uint kKindTwoThree = 0u;  // FlipKind's order
const uint kKindThreeTwo = 1u;
const uint kKindFourFour = 2u;
const uint kKindTwoTwo = 3u;
const uint kBoxSideLink = 0xfeu;
const uint kNoLink = 0xffu;

// tet_flips.cpp's kOtherPair[i][j] = {c, d}: (i, j, c, d) an even permutation of (0, 1, 2, 3).
const uint kOtherPair[32] = uint[32](0u, 0u, 2u, 3u, 3u, 1u, 1u, 2u,
                                     3u, 2u, 0u, 0u, 0u, 3u, 2u, 0u,
                                     1u, 3u, 3u, 0u, 0u, 0u, 0u, 1u,
                                     2u, 1u, 0u, 2u, 1u, 0u, 0u, 0u);
// bestFlipAt's edges, in its order.
const uvec2 kEdges[6] = uvec2[6](uvec2(0u, 1u), uvec2(0u, 2u), uvec2(0u, 3u), uvec2(1u, 2u), uvec2(1u, 3u), uvec2(2u, 3u));

// The vertex of w other than a, b and c (all three in w): the sum wraps around exactly.
uint fourthVertex(uvec4 w, uint a, uint b, uint c) { return w.x + w.y + w.z + w.w - a - b - c; }
// The entry of n (a tet's neighbours) across the face opposite vertex v of its vertices tv.
uint acrossFrom(uvec4 tv, uvec4 n, uint v) { return tv.x == v ? n.x : tv.y == v ? n.y : tv.z == v ? n.z : n.w; }
// The position of v in t (core's positionIn; v is there).
uint positionIn(uvec4 t, uint v) { return t.x == v ? 0u : t.y == v ? 1u : t.z == v ? 2u : 3u; }
// t with vertex `old` replaced by v, and t with position k replaced by v.
uvec4 replacedVertex(uvec4 t, uint old, uint v) {
    return uvec4(t.x == old ? v : t.x, t.y == old ? v : t.y, t.z == old ? v : t.z, t.w == old ? v : t.w);
}
uvec4 replacedAt(uvec4 t, uint k, uint v) {
    return uvec4(k == 0u ? v : t.x, k == 1u ? v : t.y, k == 2u ? v : t.z, k == 3u ? v : t.w);
}
// Face f of t (its vertices but t[f]) as a sorted triple.
uvec3 sortedFace(uvec4 t, uint f) {
    const uvec3 v = f == 0u ? t.yzw : f == 1u ? t.xzw : f == 2u ? t.xyw : t.xyz;
    const uint lo = min(min(v.x, v.y), v.z), hi = max(max(v.x, v.y), v.z);
    return uvec3(lo, v.x + v.y + v.z - lo - hi, hi);
}

// The ring of the edge (t[i], t[j]) as core's edgeRingOf(…, max_degree = 4); false when longer.
struct EdgeRing {
    uint p, q;
    uint degree;
    bool interior;
    uint tets[4];
    uint ring[5];
};
EdgeRing ring;

bool edgeRingOf(uint t, uvec4 start, uint i, uint j) {
    ring.p = start[i];
    ring.q = start[j];
    ring.tets[0] = t;
    ring.ring[0] = start[kOtherPair[(i * 4u + j) * 2u]];
    ring.ring[1] = start[kOtherPair[(i * 4u + j) * 2u + 1u]];
    ring.degree = 1u;
    ring.interior = false;
    const uvec4 start_neighbours = neighboursOf(t);
    uvec4 v = start, n = start_neighbours;
    // Forward: step w leaves T_w across its face opposite r_w; the ring has w + 1 tets.
    [[unroll]] for (uint w = 0u; w < 4u; ++w) {
        const uint next = acrossFrom(v, n, ring.ring[w]);
        if (next == t) {
            ring.interior = true;
            return true;
        }
        if (next == kNoTet) break;
        if (w == 3u) return false;
        v = verticesOf(next);
        n = neighboursOf(next);
        ring.tets[w + 1u] = next;
        ring.ring[w + 2u] = fourthVertex(v, ring.p, ring.q, ring.ring[w + 1u]);
        ring.degree = w + 2u;
    }
    // A boundary edge: backward from t across the face opposite y to the other end.
    uint backward[4], backward_ring[4];
    uint backward_count = 0u;
    v = start;
    n = start_neighbours;
    uint x = ring.ring[0], y = ring.ring[1];
    [[unroll]] for (uint w = 0u; w < 4u; ++w) {
        const uint previous = acrossFrom(v, n, y);
        if (previous == kNoTet) break;
        if (ring.degree + w == 4u) return false;
        v = verticesOf(previous);
        n = neighboursOf(previous);
        const uint z = fourthVertex(v, ring.p, ring.q, x);
        backward[w] = previous;
        backward_ring[w] = z;
        backward_count = w + 1u;
        y = x;
        x = z;
    }
    if (backward_count == 0u) return true;
    // Prepend the backward tets, nearest to t last: entry k is backward[count − 1 − k] for
    // k < count, else forward entry k − count.
    uint tets[4], vertices[5];
    [[unroll]] for (uint k = 0u; k < 5u; ++k) {
        uint tet = kNoTet, vertex = 0u;
        [[unroll]] for (uint m = 0u; m < 4u; ++m) {
            if (m + k + 1u == backward_count) {
                tet = backward[m];
                vertex = backward_ring[m];
            }
            if (k < 4u && m + backward_count == k) tet = ring.tets[m];
        }
        [[unroll]] for (uint m = 0u; m < 5u; ++m)
            if (m + backward_count == k) vertex = ring.ring[m];
        if (k < 4u) tets[k] = tet;
        vertices[k] = vertex;
    }
    ring.tets = tets;
    ring.ring = vertices;
    ring.degree += backward_count;
    return true;
}

bool flippableRing() { return ring.interior ? ring.degree == 3u || ring.degree == 4u : ring.degree == 2u; }
uint ringOwner() {
    uint owner = ring.tets[0];
    [[unroll]] for (uint k = 1u; k < 4u; ++k)
        if (k < ring.degree) owner = min(owner, ring.tets[k]);
    return owner;
}
bool ringIsFlat() {
    bool all_flat = true;
    [[unroll]] for (uint k = 0u; k < 4u; ++k)
        if (k < ring.degree) all_flat = all_flat && isFlat(ring.tets[k]);
    return all_flat;
}

// core's FlipPlan, but for the hull faces: entry 4 · a + f for face f of region tet a, set when
// that face is a hull face (hull_face bit), and links to a hull face as 4 + 4 · a + f.
struct Plan {
    uint kind;
    double gain;
    double gain_scale;
    uint region_count;
    uint region[4];
    uint new_count;
    uvec4 new_tets[4];
    int64_t new_orients[4];  // for the new tets' contents
    uint hull_faces;         // bit 4 · a + f: a hull face
    uint hull_outside[16];   // the tet across it (kNoTet on the box's side)
    uint hull_back[16];      // the entry of its neighbours that points into the region
    uint links[16];          // links[4 · i + f]: core's FlipPlan::links[i][f], hull faces as above
};
Plan plan;

bool allPositive() {
    bool positive = true;
    [[unroll]] for (uint i = 0u; i < 4u; ++i)
        if (i < plan.new_count) {
            plan.new_orients[i] = orientOf(plan.new_tets[i]);
            positive = positive && plan.new_orients[i] > 0l;
        }
    return positive;
}

// A face's term of face_scf's total and the magnitude it rounds at (tet_flips.cpp's faceTerm):
// x = scf · (c_a + c_b) / 4, y = |g_a|·|g_b| · (c_a + c_b) / 4.
dvec2 faceTerm(dvec3 ga, double content_a, dvec3 gb, double content_b) {
    precise double share = (content_a + content_b) / 4.0lf;
    precise double cost = faceScf(ga, gb) * share;
    precise double scale = normProduct(ga, gb) * share;
    return dvec2(cost, scale);
}

// Completes a plan whose kind, region and legal new tets are set (core's finishPlan): hull
// faces, links and, with `gain`, the gain and its scale. The variance gain reads the region's
// costs and the new tets alone, so with that weight the gain is all a candidate needs.
void finishPlan(bool gain) {
    if (gain && push.face_scf == 0u) {
        precise double before = 0.0lf, after = 0.0lf, content = 0.0lf;
        [[unroll]] for (uint a = 0u; a < 4u; ++a)
            if (a < plan.region_count) {
                // cachedCost's variance cost, from the record (no cost cache with this weight).
                precise double region_content = contentOf(plan.region[a]);
                precise double cost = region_content * varianceOfTet(verticesOf(plan.region[a]));
                before += cost;
                content += region_content;
            }
        [[unroll]] for (uint i = 0u; i < 4u; ++i)
            if (i < plan.new_count) {
                precise double term = contentFromOrient(plan.new_orients[i]) * varianceOfTet(plan.new_tets[i]);
                after += term;
            }
        precise double difference = before - after;
        plan.gain = difference;
        plan.gain_scale = content;
        return;
    }
    uvec4 region_vertices[4], region_neighbours[4];
    [[unroll]] for (uint a = 0u; a < 4u; ++a)
        if (a < plan.region_count) {
            region_vertices[a] = verticesOf(plan.region[a]);
            region_neighbours[a] = neighboursOf(plan.region[a]);
        }
    // Old faces, in core's order (a, then f): inside the region (counted once, at the tet with
    // the smaller index: inner_index) or on its hull.
    uint inner_faces = 0u;  // bit 4 · a + f: an inner face with a < b
    uint inner_index[16];
    uvec3 hull_face[16];
    plan.hull_faces = 0u;
    [[unroll]] for (uint a = 0u; a < 4u; ++a)
        [[unroll]] for (uint f = 0u; f < 4u; ++f) {
            const uint e = 4u * a + f;
            if (a >= plan.region_count) continue;
            const uint n = region_neighbours[a][f];
            uint b = 4u;
            [[unroll]] for (uint c = 0u; c < 4u; ++c)
                if (c < plan.region_count && plan.region[c] == n) b = c;
            inner_index[e] = b;
            if (b < 4u) {
                if (b > a) inner_faces |= 1u << e;
                continue;
            }
            plan.hull_faces |= 1u << e;
            hull_face[e] = sortedFace(region_vertices[a], f);
            plan.hull_outside[e] = n;
            plan.hull_back[e] = n == kNoTet ? 0u : positionIn(neighboursOf(n), plan.region[a]);
        }
    // New faces: shared with another new tet, else a hull face, else (2–2) on the box's side.
    uvec3 new_face[16];
    [[unroll]] for (uint i = 0u; i < 4u; ++i)
        [[unroll]] for (uint f = 0u; f < 4u; ++f) new_face[4u * i + f] = sortedFace(plan.new_tets[i], f);
    [[unroll]] for (uint i = 0u; i < 4u; ++i)
        [[unroll]] for (uint f = 0u; f < 4u; ++f) {
            uint link = kNoLink;
            [[unroll]] for (uint j = 0u; j < 4u; ++j)
                [[unroll]] for (uint g = 0u; g < 4u; ++g)
                    if (link == kNoLink && j < plan.new_count && j != i && new_face[4u * j + g] == new_face[4u * i + f])
                        link = j;
            [[unroll]] for (uint e = 0u; e < 16u; ++e)
                if (link == kNoLink && (plan.hull_faces & (1u << e)) != 0u && hull_face[e] == new_face[4u * i + f])
                    link = 4u + e;
            plan.links[4u * i + f] = link == kNoLink ? kBoxSideLink : link;
        }
    if (!gain) return;

    dvec3 region_gradient[4], new_gradient[4];
    double region_content[4], new_content[4];
    [[unroll]] for (uint a = 0u; a < 4u; ++a)
        if (a < plan.region_count) {
            region_gradient[a] = gradientOf(plan.region[a]);
            region_content[a] = contentOf(plan.region[a]);
        }
    [[unroll]] for (uint i = 0u; i < 4u; ++i)
        if (i < plan.new_count) {
            new_gradient[i] = gradientOfTet(plan.new_tets[i]);
            new_content[i] = contentFromOrient(plan.new_orients[i]);
        }
    precise double before = 0.0lf, after = 0.0lf, scale = 0.0lf;
    [[unroll]] for (uint e = 0u; e < 16u; ++e)
        if ((inner_faces & (1u << e)) != 0u) {
            dvec3 gb = dvec3(0.0lf);
            double cb = 0.0lf;
            [[unroll]] for (uint c = 0u; c < 4u; ++c)
                if (inner_index[e] == c) {
                    gb = region_gradient[c];
                    cb = region_content[c];
                }
            const dvec2 term = faceTerm(region_gradient[e / 4u], region_content[e / 4u], gb, cb);
            before += term.x;
            scale += term.y;
        }
    [[unroll]] for (uint e = 0u; e < 16u; ++e)
        if ((plan.hull_faces & (1u << e)) != 0u && plan.hull_outside[e] != kNoTet) {
            const uint o = plan.hull_outside[e];
            const dvec2 term = faceTerm(region_gradient[e / 4u], region_content[e / 4u], gradientOf(o), contentOf(o));
            before += term.x;
            scale += term.y;
        }
    [[unroll]] for (uint i = 0u; i < 4u; ++i)
        [[unroll]] for (uint f = 0u; f < 4u; ++f) {
            if (i >= plan.new_count) continue;
            const uint link = plan.links[4u * i + f];
            if (link == kBoxSideLink || link <= i) continue;  // a box side, or counted at the other tet
            dvec3 gb;
            double cb;
            if (link < 4u) {
                gb = new_gradient[0];
                cb = new_content[0];
                [[unroll]] for (uint j = 1u; j < 4u; ++j)
                    if (link == j) {
                        gb = new_gradient[j];
                        cb = new_content[j];
                    }
            } else {
                uint o = kNoTet;
                [[unroll]] for (uint e = 0u; e < 16u; ++e)
                    if (link == 4u + e) o = plan.hull_outside[e];
                if (o == kNoTet) continue;
                gb = gradientOf(o);
                cb = contentOf(o);
            }
            const dvec2 term = faceTerm(new_gradient[i], new_content[i], gb, cb);
            after += term.x;
            scale += term.y;
        }
    precise double difference = before - after;
    plan.gain = difference;
    plan.gain_scale = scale;
}

// The plan's region and new tets of the 2–3 at face `face` of t (core's planTwoThreeImpl);
// false when illegal.
bool planTwoThree(uint t, uint face) {
    const uvec4 tv = verticesOf(t);
    const uint n = neighboursOf(t)[face];
    plan.kind = kKindTwoThree;
    plan.region_count = 2u;
    plan.region[0] = t;
    plan.region[1] = n;
    const uint e = acrossFrom(neighboursOf(n), verticesOf(n), t);  // n's vertex opposite the face
    plan.new_count = 3u;
    [[unroll]] for (uint i = 0u; i < 3u; ++i) plan.new_tets[i] = replacedAt(tv, i < face ? i : i + 1u, e);
    return allPositive();
}

// 3–2 and 2–2: T_0 with q, then p, replaced by r_2 (core's planRingToFace).
bool planRingToFace(uint t, uint kind) {
    plan.kind = kind;
    plan.region_count = ring.degree;
    plan.region = ring.tets;
    if (plan.region[0] != t) {  // 2–2 seen from T_1
        plan.region[0] = ring.tets[1];
        plan.region[1] = ring.tets[0];
    }
    if (kind == kKindTwoTwo && orientOf(ring.p, ring.q, ring.ring[0], ring.ring[2]) != 0l) return false;
    const uvec4 t0 = verticesOf(ring.tets[0]);
    plan.new_count = 2u;
    plan.new_tets[0] = replacedVertex(t0, ring.q, ring.ring[2]);
    plan.new_tets[1] = replacedVertex(t0, ring.p, ring.ring[2]);
    return allPositive();
}

// The 4–4 to diagonal j (core's planFourFourOf); the caller checked the ring is coplanar.
bool planFourFour(uint j) {
    plan.kind = kKindFourFour;
    plan.region_count = 4u;
    plan.region = ring.tets;
    const uint far = j == 0u ? ring.ring[2] : ring.ring[3];
    // The ring tets holding r_j: j and j + 3 (mod 4).
    const uvec4 first = verticesOf(j == 0u ? ring.tets[0] : ring.tets[1]);
    const uvec4 second = verticesOf(j == 0u ? ring.tets[3] : ring.tets[0]);
    plan.new_count = 4u;
    plan.new_tets[0] = replacedVertex(first, ring.p, far);
    plan.new_tets[1] = replacedVertex(first, ring.q, far);
    plan.new_tets[2] = replacedVertex(second, ring.p, far);
    plan.new_tets[3] = replacedVertex(second, ring.q, far);
    return allPositive();
}

bool worthApplying() {
    precise double bar = 1e-12lf * plan.gain_scale;  // kTetFlipGainThreshold · gain_scale
    return plan.gain > bar;
}

// The best owned flip of tet t (core's bestOwnedFlipAt): its site and gain; false if none.
// One pass over 16 attempts, each ending in the one call of finishPlan: faces 0–3, then for each
// edge k attempts 4 + 2k (its ring's flip, or the 4–4 to diagonal 0) and 5 + 2k (the 4–4 to
// diagonal 1, where core's planEdgeImpl picks the better and considers it in edge k's place).
bool bestOwnedFlip(uint t, out uint best_site, out double best_gain) {
    const uvec4 tv = verticesOf(t);
    const uvec4 tn = neighboursOf(t);
    const bool t_flat = isFlat(t);
    bool found = false;
    best_site = 0u;
    best_gain = 0.0lf;
    bool edge_open = false;  // the ring of this edge is owned, flippable, not all flat (and coplanar if of degree 4)
    bool first_legal = false;
    double first_gain = 0.0lf, first_scale = 0.0lf;
    for (uint attempt = 0u; attempt < 16u; ++attempt) {
        uint site;
        bool legal;
        const uint k = (attempt - 4u) / 2u, diagonal = attempt % 2u;
        if (attempt < 4u) {
            const uint n = tn[attempt];
            if (n == kNoTet || n < t || (t_flat && isFlat(n))) continue;
            site = attempt;
            legal = planTwoThree(t, attempt);
        } else if (diagonal == 0u) {
            edge_open = edgeRingOf(t, tv, kEdges[k].x, kEdges[k].y) && flippableRing() && ringOwner() == t && !ringIsFlat();
            if (edge_open && ring.degree == 4u)
                edge_open = orientOf(ring.ring[0], ring.ring[1], ring.ring[2], ring.ring[3]) == 0l;
            if (!edge_open) continue;
            site = kTetSiteEdge + k;
            if (ring.degree == 4u) legal = planFourFour(0u);
            else legal = planRingToFace(t, ring.interior ? kKindThreeTwo : kKindTwoTwo);
        } else {
            if (!edge_open || ring.degree != 4u) continue;
            site = kTetSiteDiagonal + k;
            legal = planFourFour(1u);
        }
        if (legal) finishPlan(true);
        if (attempt >= 4u && ring.degree == 4u) {
            if (diagonal == 0u) {  // wait for diagonal 1
                first_legal = legal;
                first_gain = plan.gain;
                first_scale = plan.gain_scale;
                continue;
            }
            if (!first_legal && !legal) continue;
            if (first_legal && !(legal && plan.gain > first_gain)) {
                site = kTetSiteEdge + k;
                plan.gain = first_gain;
                plan.gain_scale = first_scale;
            }
        } else if (!legal) {
            continue;
        }
        if (worthApplying() && (!found || plan.gain > best_gain)) {
            found = true;
            best_site = site;
            best_gain = plan.gain;
        }
    }
    return found;
}

// The plan of an owner's site as bestOwnedFlip found it (legal then), without the gain.
void planOfSite(uint t, uint site) {
    if (site < kTetSiteEdge) {
        planTwoThree(t, site);
    } else {
        const uint k = site < kTetSiteDiagonal ? site - kTetSiteEdge : site - kTetSiteDiagonal;
        edgeRingOf(t, verticesOf(t), kEdges[k].x, kEdges[k].y);
        if (ring.degree != 4u) planRingToFace(t, ring.interior ? kKindThreeTwo : kKindTwoTwo);
        else if (site < kTetSiteDiagonal) planFourFour(0u);
        else planFourFour(1u);
    }
    finishPlan(false);
}

// The read set of an owner's site (FlipPlan::readSet, in another order) and its kind.
uint readSetOfSite(uint t, uint site, out uint read[12], out uint kind) {
    uint region[4];
    uint region_count;
    if (site < kTetSiteEdge) {
        kind = kKindTwoThree;
        region[0] = t;
        region[1] = neighboursOf(t)[site];
        region_count = 2u;
    } else {
        const uint k = site < kTetSiteDiagonal ? site - kTetSiteEdge : site - kTetSiteDiagonal;
        edgeRingOf(t, verticesOf(t), kEdges[k].x, kEdges[k].y);
        kind = ring.degree == 4u ? kKindFourFour : ring.interior ? kKindThreeTwo : kKindTwoTwo;
        region_count = ring.degree;
        region = ring.tets;
    }
    uint count = 0u;
    [[unroll]] for (uint a = 0u; a < 4u; ++a)
        if (a < region_count) read[count++] = region[a];
    [[unroll]] for (uint a = 0u; a < 4u; ++a) {
        if (a >= region_count) continue;
        const uvec4 n = neighboursOf(region[a]);
        [[unroll]] for (uint f = 0u; f < 4u; ++f) {
            bool inside = n[f] == kNoTet;
            [[unroll]] for (uint b = 0u; b < 4u; ++b) inside = inside || (b < region_count && region[b] == n[f]);
            if (!inside) read[count++] = n[f];
        }
    }
    return count;
}
