// Bindings, push constants and constants of the simplification kernels (glsl/simplify/), shared
// by them and the host (compute/simplify/). They have their own pipeline layout: the
// optimisation's bindings (glsl/layout.h) are not theirs. Every array is a storage texel buffer,
// for the reasons glsl/layout.h gives.
#ifndef DDTUP_SIMPLIFY_LAYOUT_H
#define DDTUP_SIMPLIFY_LAYOUT_H

#ifdef __cplusplus
#include <cstdint>
namespace ddt {
typedef uint32_t uint;
#endif

// core/simplify/edge_collapse.h's kMaxCollapseValence (the host checks that they agree): it
// bounds the walks of one invocation, which handles one edge, to about 2 · 68 + 34² loop
// iterations, far below lavapipe's 65 535 (glsl/layout.h).
const uint kCollapseValenceBound = 64u;
// Doubles per vertex in the quadric array: core's Quadric as it is (A's upper triangle, b, c,
// the area).
const uint kQuadricDoubles = 29u;

const uint kSimplifyBindingEdgeVertices = 0u;    // rgba32ui per edge: a, b, l, r (core/image/mesh.h)
const uint kSimplifyBindingEdgeNeighbours = 1u;  // rgba32ui per edge: bl, la, ar, rb
const uint kSimplifyBindingVertexFirst = 2u;     // r32ui per vertex: where its walk starts (VertexEdges)
const uint kSimplifyBindingValues = 3u;          // rgba32f per vertex: its channels
const uint kSimplifyBindingQuadrics = 4u;        // rg32ui: kQuadricDoubles doubles per vertex, each as two words
const uint kSimplifyBindingCandidates = 5u;      // rgba32ui per edge: key's cost word, key's tie word, kCandidate… bits, edge
const uint kSimplifyBindingLeastCost = 6u;       // r32ui per vertex: the least cost word of the regions holding it
const uint kSimplifyBindingLeastTie = 7u;        // r32ui per vertex: the least tie word among keys of that cost word
const uint kSimplifyBindingWinners = 8u;         // 2 rgba32ui per winner, in no order: its candidate, its target
const uint kSimplifyBindingCollapses = 9u;       // r32ui per collapse to make: its edge | kCollapse… bits
const uint kSimplifyBindingChanged = 10u;        // r32ui per vertex: 1 if the last round's collapses changed its edges
const uint kSimplifyBindingTallies = 11u;        // r32ui: kCostBins keys per bin, kTallyWinners, kTallyListed
const uint kSimplifyBindingListed = 12u;         // r32ui per listed edge, in no order (gather_edges.comp)
const uint kSimplifyBindingTaken = 13u;          // r32ui per vertex: 1 in a winner's region
const uint kSimplifyBindingEdgeState = 14u;      // r32ui per edge in a selection: kEdgeUndecided, …
const uint kSimplifyBindingPositions = 15u;      // rg32i per vertex: its position (core/image/mesh.h, explicit)
const uint kSimplifyBindingTargets = 16u;        // rg32i per edge: its candidate's target, where it moves
const uint kSimplifyBindingCount = 17u;
// Bits of a candidate's third word: b into a; the merged vertex moves (to its target).
const uint kCandidateBIntoA = 1u;
const uint kCandidateMoves = 2u;
// Bits of a collapse entry (below them, the edge): b into a; the merged vertex moves.
const uint kCollapseBIntoA = 0x80000000u;
const uint kCollapseMoves = 0x40000000u;
// The most edges at the vertex a legal collapse removes: with the collapse's own edge and the
// removed ones, it leaves at most kCollapseValenceBound at the other (which has two or more).
const uint kMaxEdgesAtFrom = kCollapseValenceBound + 4u;

// Steps of select_collapses.comp: the keys counted by their cost word's bin; then, in each pass
// over the undecided keys (among those whose cost word is at most a limit), a vertex's least
// 64-bit key, (cost word, tie word), in two 32-bit atomic minima (no 64-bit atomics needed),
// the winners, and the undecided edges whose regions touch a winner's, which are out.
const uint kSelectTallyCosts = 0u;
const uint kSelectLeastCost = 1u;
const uint kSelectLeastTie = 2u;
const uint kSelectWinners = 3u;
const uint kSelectOut = 4u;
// An edge's state in a selection.
const uint kEdgeUndecided = 0u;
const uint kEdgeWon = 1u;
const uint kEdgeOut = 2u;
// A cost word's bin is its high 16 bits (a non-negative double's sign, exponent and 4 bits of
// mantissa: bins 1/16 of an octave wide), the last bin taking every word beyond.
const uint kCostBins = 0x8000u;
// A collapse key's low word, which orders equal cost words: a bijection of the edge id (keys
// stay unique, and the order is the same on every device), not the id itself. Edge ids follow
// the grid's rows, and a key wins only where no smaller one is near, so in a flat region
// (every cost 0) ids made one row of its edges win a round: astronaut.png to 10 % took 2099
// rounds. The mixing steps are Wellons' "lowbias32" (his hash-prospector), each invertible.
#ifdef __cplusplus
inline
#endif
uint tieOrder(uint edge) {
    uint x = edge;
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// The tallies after the bins: the winners listed, and the edges listed.
const uint kTallyWinners = kCostBins;
const uint kTallyListed = kCostBins + 1u;
const uint kTallyWords = kCostBins + 2u;

// Steps of gather_edges.comp: the edges whose candidate may have changed (not removed, with
// an end marked changed; or removed, with a candidate still), or the edges whose cost word is
// at most push.cost_word_limit.
const uint kGatherChanged = 0u;
const uint kGatherLimited = 1u;
#ifdef __cplusplus
inline
#endif
uint costBin(uint cost_word) { return cost_word >> 16 < kCostBins ? cost_word >> 16 : kCostBins - 1u; }

struct SimplifyPush {
    uint width;
    uint height;
    uint channels;
    uint edge_count;  // edges; the listed edges' count where `listed`; for collapse_edges.comp, collapses
    uint first_edge;  // the dispatch's first edge (collapse): one invocation each, in several dispatches
    uint step;        // select_collapses.comp: kSelect…
    uint cost_word_limit;  // select_collapses.comp: the greatest cost word that takes part
    uint listed;           // 1: invocation i works on the listed edge i (kSimplifyBindingListed)
    uint error_limit_low;  // collapse_candidates.comp: exceedsErrorLimit's limit, a double's low
    uint error_limit_high; // and high word
    uint locked_sides;     // Mesh::locked_sides
};

#ifdef __cplusplus
}  // namespace ddt
#endif
#endif
