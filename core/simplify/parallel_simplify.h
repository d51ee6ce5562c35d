// The parallel simplification rule, on the CPU: what the Vulkan kernels (compute/simplify/)
// compute too, bit for bit, round by round, with the same result whatever the number of
// threads. It replaces the paper's lock-free skip list and k-d tree partitions, which make
// the order of collapses, and so the mesh, depend on thread timing.
//
// Each round:
// 1. candidates: every edge's best legal collapse (canCollapse; the cheaper direction, b into
//    a on ties), keyed by (its cost cut to 32 bits, its edge id);
// 2. select: a collapse's region is its two vertices and all their neighbours, which holds
//    every record the collapse writes and everything its legality reads (edge_collapse.h).
//    Each vertex takes the least key among the regions that hold it; a collapse wins where it
//    holds the least key of every vertex of its region, so winners' regions are disjoint and
//    they collapse in any order to the same mesh;
// 3. collapse: the winners with the least keys, as many as the target still needs; then
//    their quadrics are merged.
// Only edges with an end in the ring of a collapse's `from` get a new candidate: nothing else
// their candidate reads changed. Selection looks at the least keys only, which gives the same
// winners (selectWinners) with far fewer region walks.
// Until the target is reached or no legal collapse is left; the mesh is then compacted by a
// stable prefix sum (edge_collapse.h), not by the paper's swap-with-last, so ids keep their
// order and "ties by id" keeps its meaning.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "greedy_simplify.h"
#include "vertex_quadrics.h"

namespace ddt {

struct ParallelSimplifyStats : SimplifyStats {
    uint32_t rounds = 0;
};

// Step 1's result for one edge: the key of its best legal collapse, kNoCollapseKey if it has
// none (or was removed), and its direction. A collapse that exceeds `error_limit`
// (exceedsErrorLimit; 0: none) is not a candidate.
constexpr uint64_t kNoCollapseKey = UINT64_MAX;
struct CollapseCandidate {
    uint64_t key = kNoCollapseKey;
    bool b_into_a = true;

    bool operator==(const CollapseCandidate&) const = default;
};
CollapseCandidate bestCollapse(const Mesh& mesh, const SimplifyStart& start, uint32_t edge, double error_limit = 0.0);

// Step 2's result among the keys at most `limit`: the edges whose key is the least of every
// vertex in their region, ascending. Only keys at most `limit` take part, and that changes no
// winner at most `limit`: a key that keeps one from winning is smaller, so it takes part too.
std::vector<uint32_t> selectWinners(const Mesh& mesh, const VertexEdges& edges, const std::vector<uint64_t>& keys,
                                    uint64_t limit = kNoCollapseKey);

// The `count`-th least key (kNoCollapseKey if there are no more keys than that).
uint64_t keyLimitFor(std::vector<uint64_t> keys, size_t count);

// How many collapses a round makes at most, with `vertices` left: as many as the target still
// needs and at most 1/64 of the vertices.
size_t roundCollapses(uint32_t vertices, uint32_t target);

// Step 3's choice: keeps the least winners, roundCollapses of them at most, in key order.
void leastWinners(std::vector<uint32_t>& winners, const std::vector<uint64_t>& keys, uint32_t vertices,
                  uint32_t target);

// How many of the least keys take part in a round's selection, per collapse the round needs,
// at least: winners are rarer than keys, since their regions must hold no smaller key, and
// rarest among the least keys, which lie together in flat regions (chelsea.png to 10 %: 20 to
// 60 keys per winner).
constexpr size_t kLeastKeysPerCollapse = 4;

// Step 2's search for `needed` winners among the least keys: select(count) gives the winners
// among at least the `count` least keys and whether those were all keys (a pair). The count
// starts at the last round's keys_per_collapse per collapse needed and grows by half while
// too few win; by selectWinners' argument the `needed` least winners are then the rule's.
// (Starting lower costs more selections than it saves: chelsea.png to 10 % on lavapipe
// selected 291 times in 147 rounds from half the last round's, 154 times from all of it.)
template <typename Select>
auto winnersAmongLeastKeys(size_t needed, size_t& keys_per_collapse, Select select) {
    keys_per_collapse = std::max(kLeastKeysPerCollapse, keys_per_collapse);
    for (;; keys_per_collapse += keys_per_collapse / 2) {
        auto [winners, all_keys] = select(keys_per_collapse * needed);
        if (winners.size() >= needed || all_keys) return winners;
    }
}

// The cost a key holds: its double, cut.
double collapseKeyCost(uint64_t key);

// As simplifySerial, by the parallel rule: collapses that exceed `max_error` are no
// candidates, so simplification ends where no other is left.
ParallelSimplifyStats simplifyParallel(Mesh& mesh, Image& values, uint32_t target, double max_error = 0.0);

}  // namespace ddt
