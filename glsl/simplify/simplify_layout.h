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

const uint kSimplifyBindingEdgeVertices = 0u;    // rgba32ui per edge: a, b, l, r (core/mesh.h)
const uint kSimplifyBindingEdgeNeighbours = 1u;  // rgba32ui per edge: bl, la, ar, rb
const uint kSimplifyBindingVertexFirst = 2u;     // r32ui per vertex: where its walk starts (VertexEdges)
const uint kSimplifyBindingValues = 3u;          // rgba32f per vertex: its channels
const uint kSimplifyBindingQuadrics = 4u;        // rg32ui: kQuadricDoubles doubles per vertex, each as two words
const uint kSimplifyBindingCandidates = 5u;      // rgba32ui per edge: key's cost word, key's id word, b into a
const uint kSimplifyBindingLeastCost = 6u;       // r32ui per vertex: the least cost word of the regions holding it
const uint kSimplifyBindingLeastId = 7u;         // r32ui per vertex: the least edge id among keys of that cost word
const uint kSimplifyBindingWinners = 8u;         // r32ui per edge: 1 where its key is the least of its whole region
const uint kSimplifyBindingCollapses = 9u;       // r32ui per collapse to make: its edge, bit 31 set for b into a
const uint kSimplifyBindingChanged = 10u;        // r32ui per vertex: 1 if in the region of one of the last round's collapses
const uint kSimplifyBindingCount = 11u;
// Bit of a collapse entry: b into a.
const uint kCollapseBIntoA = 0x80000000u;
// The most edges at the vertex a legal collapse removes: with the collapse's own edge and the
// removed ones, it leaves at most kCollapseValenceBound at the other (which has two or more).
const uint kMaxEdgesAtFrom = kCollapseValenceBound + 4u;

// Steps of select_collapses.comp: a vertex's least 64-bit key, (cost word, id), in two 32-bit
// atomic minima (no 64-bit atomics needed), then the winners.
const uint kSelectLeastCost = 0u;
const uint kSelectLeastId = 1u;
const uint kSelectWinners = 2u;

struct SimplifyPush {
    uint width;
    uint height;
    uint channels;
    uint edge_count;  // edges; for collapse_edges.comp, collapses
    uint first_edge;  // the dispatch's first edge (collapse): one invocation each, in several dispatches
    uint step;        // select_collapses.comp: kSelect…
};

#ifdef __cplusplus
}  // namespace ddt
#endif
#endif
