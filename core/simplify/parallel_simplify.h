// The parallel simplification rule, on the CPU: what the Vulkan kernels (compute/simplify/)
// compute too, bit for bit, round by round, with the same result whatever the number of
// threads. It replaces the paper's lock-free skip list and k-d tree partitions, which make
// the order of collapses, and so the mesh, depend on thread timing.
//
// Each round:
// 1. candidates: every edge's best legal collapse (canCollapse, with the merged vertex placed
//    by placeCollapses; the cheaper direction, b into a on ties), keyed by (its cost cut to
//    32 bits, tieOrder of its edge id);
// 2. select among the cheapest: the keys in the least cost bins (costBin: 1/16 of an octave
//    wide) that hold kKeysPerCollapse keys per collapse the round makes, or all keys, take
//    part. A collapse's region is its two vertices and all their neighbours, which holds every
//    record the collapse writes and everything its legality reads (edge_collapse.h). In each
//    of kSelectionPasses passes, each vertex takes the least key among the undecided regions
//    that hold it; a collapse wins where it holds the least key of every vertex of its region,
//    and the undecided ones whose regions touch a winner's are out. Winners' regions are
//    disjoint, so they collapse in any order to the same mesh;
// 3. collapse: the winners with the least keys, as many as the round makes (roundCollapses);
//    then their quadrics are merged.
// Until the target is reached or no legal collapse is left; the mesh is then compacted by a
// stable prefix sum (edge_collapse.h), not by the paper's swap-with-last, so ids keep their
// order (the ties' order is a function of the ids).
//
// Why among the cheapest, and in passes (measured with the merged vertex at an endpoint, before
// placement.h): costs change slowly across a mesh, so the least keys
// of overlapping regions form long descending chains, each ending in one winner. Over all
// keys in one pass (and at most 1/64 of the vertices a round), astronaut.png to 10 % found 37
// winners among 97 000 keys in its 300th round and took 434 rounds (chelsea.png 147), and the
// winners were then costly ones: 34.10 dB against the serial reference's 37.08 (PSNR of the
// render against the original). Each pass ends the chains' next links, and the cheapest keys
// alone keep the winners cheap: 37.11 dB in 174 rounds (chelsea.png 36.45 dB against 36.46,
// 148 rounds), and at most 1/32 a round 37.08 dB in 106 (36.43 dB in 77). Choosing winners
// among the cheapest by a scattered order (tieOrder alone) gave as many winners but lost
// 0.8 dB on a 100 × 70 photograph at 5 %, where these stay within 0.1 dB.
//
// Only edges with an end in the ring of a collapse's `from` get a new candidate: nothing else
// their candidate reads changed (markRingChanged).
#pragma once

#include <cstdint>
#include <vector>

#include "greedy_simplify.h"
#include "simplify/simplify_layout.h"
#include "vertex_quadrics.h"

namespace ddt {

struct ParallelSimplifyStats : SimplifyStats {
    uint32_t rounds = 0;
};

// Step 1's result for one edge: the key of its best legal collapse (placed by placeCollapses),
// kNoCollapseKey if it has none (or was removed), its direction and where the merged vertex
// goes. A collapse that exceeds `error_limit` (exceedsErrorLimit; 0: none) is not a candidate.
constexpr uint64_t kNoCollapseKey = UINT64_MAX;
struct CollapseCandidate {
    uint64_t key = kNoCollapseKey;
    bool b_into_a = true;
    bool moves = false;
    Position target = {0, 0};

    bool operator==(const CollapseCandidate&) const = default;
};
CollapseCandidate bestCollapse(const Mesh& mesh, const SimplifyStart& start, uint32_t edge, double error_limit = 0.0);

// How many collapses a round makes at most, with `vertices` left: as many as the target still
// needs and at most 1/32 of the vertices.
size_t roundCollapses(uint32_t vertices, uint32_t target);

// Step 2's share: how many of the cheapest keys take part, per collapse the round makes, and
// its passes (measured in the comment above).
constexpr size_t kKeysPerCollapse = 3;
constexpr uint32_t kSelectionPasses = 3;

// Keys per cost bin (costBin of the key's cost word; kCostBins of them).
std::vector<uint32_t> costTally(const std::vector<uint64_t>& keys);
// The greatest cost word of the least bins of `tally` that hold at least `count` keys, or
// kAllCostWords where that takes every key.
constexpr uint32_t kAllCostWords = 0xFFFFFFFEu;
uint32_t costWordLimit(const std::vector<uint32_t>& tally, size_t count);

// Step 2's winners among the keys whose cost word is at most `limit`, ascending by edge.
std::vector<uint32_t> selectWinners(const Mesh& mesh, const VertexEdges& edges, const std::vector<uint64_t>& keys,
                                    uint32_t limit);

// Step 3's choice: keeps the least winners, roundCollapses of them at most, in key order.
void leastWinners(std::vector<uint32_t>& winners, const std::vector<uint64_t>& keys, uint32_t vertices,
                  uint32_t target);

// The cost a key holds: its double, cut.
double collapseKeyCost(uint64_t key);

// As simplifySerial, by the parallel rule: collapses that exceed `max_error` are no
// candidates, so simplification ends where no other is left.
ParallelSimplifyStats simplifyParallel(Mesh& mesh, Image& values, uint32_t target, double max_error = 0.0);

}  // namespace ddt
