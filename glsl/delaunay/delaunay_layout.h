// Bindings, push constants and constants of the Delaunay flip kernels (glsl/delaunay/), shared
// by them and the host (compute/delaunay/). Their own pipeline layout; every array a storage
// texel buffer (glsl/layout.h says why). The edge records are r32ui, four words an edge, not
// rgba32ui: two flips in one round may rewrite the two sides of one neighbour edge, and each
// must store only its own side's words.
#ifndef DDTUP_DELAUNAY_LAYOUT_H
#define DDTUP_DELAUNAY_LAYOUT_H

#include "../layout.h"
#include "../simplify/simplify_layout.h"

#ifdef __cplusplus
#include <cstdint>
namespace ddt {
typedef uint32_t uint;
#endif

const uint kDelaunayBindingEdgeVertices = 0u;    // r32ui, 4 per edge: a, b, l, r (core/image/mesh.h)
const uint kDelaunayBindingEdgeNeighbours = 1u;  // r32ui, 4 per edge: bl, la, ar, rb
const uint kDelaunayBindingPositions = 2u;       // rg32i per vertex: its position (fixed point)
const uint kDelaunayBindingEdgeStates = 3u;      // r32ui per edge: kEdge… below
const uint kDelaunayBindingTallies = 4u;         // r32ui, 2 per round of a batch: edges marked, flipped
const uint kDelaunayBindingEdgeLists = 5u;       // r32ui, 2 × edges: the two work lists, list i at i × edges
const uint kDelaunayBindingListLengths = 6u;     // r32ui, 2: the work lists' lengths
const uint kDelaunayBindingDispatchArgs = 7u;    // r32ui, 4 per slot (VkDispatchIndirectCommand, padded):
                                                 // delaunayDispatches(edges) slots per work list
const uint kDelaunayBindingCount = 8u;

// An edge's state within a round: marked by delaunay_mark.comp, chosen by delaunay_select.comp.
const uint kEdgeLocallyDelaunay = 0u;
const uint kEdgeMustFlip = 1u;
const uint kEdgeFlipsNow = 2u;
// A bit beside the state: the edge is on the next round's work list already.
const uint kEdgeQueued = 4u;
const uint kEdgeStateMask = 3u;

// Rounds recorded in one command buffer, submitted until a round marks nothing. Round r works
// through list r % 2 and fills the other (an even count, so every batch starts on list 0).
// Rounds after the last with marks have empty lists and dispatch no groups; 16 keeps their
// cost (four dispatches each, about 80 µs on lavapipe) small next to a host round trip per round.
const uint kDelaunayRoundsPerBatch = 16u;

// The dispatches one pass over `edges` edges takes: at most kMaxGroups groups each.
#ifdef __cplusplus
inline
#endif
uint delaunayDispatches(uint edges) {
    const uint per_dispatch = kMaxGroups * kGroupSize;
    return edges / per_dispatch + (edges % per_dispatch != 0u ? 1u : 0u);
}

// The order in which marked edges win a round: an edge flips if its priority is below every
// marked edge's sharing a triangle with it. A bijection of the id (simplify_layout.h's
// tieOrder), not the id itself: the sweep numbers a fan's edges in order, and by id alone only
// the first of a chain of marked edges would flip each round. Salted by the round, so that no
// edge loses to the same neighbour round after round.
#ifdef __cplusplus
inline
#endif
uint flipPriority(uint edge, uint round) { return tieOrder(edge ^ (round * 0x9E3779B9u)); }

struct DelaunayPush {
    uint edge_count;
    uint first_edge;  // the dispatch's first edge: one invocation an edge, in several dispatches
    uint round;       // within the batch: the salt of flipPriority and the tallies' slot
    uint unused;
};

#ifdef __cplusplus
static_assert(sizeof(DelaunayPush) == 4 * 4, "DelaunayPush layout");
}  // namespace ddt
#endif
#endif
