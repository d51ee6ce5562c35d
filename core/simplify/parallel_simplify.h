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
// Until the target is reached or no legal collapse is left; the mesh is then compacted by a
// stable prefix sum (edge_collapse.h), not by the paper's swap-with-last, so ids keep their
// order and "ties by id" keeps its meaning.
#pragma once

#include <cstdint>
#include <vector>

#include "greedy_simplify.h"
#include "vertex_quadrics.h"

namespace ddt {

struct ParallelSimplifyStats : SimplifyStats {
    uint32_t rounds = 0;
};

// Step 1's result for one edge: the key of its best legal collapse, kNoCollapseKey if it has
// none (or was removed), and its direction.
constexpr uint64_t kNoCollapseKey = UINT64_MAX;
struct CollapseCandidate {
    uint64_t key = kNoCollapseKey;
    bool b_into_a = true;

    bool operator==(const CollapseCandidate&) const = default;
};
CollapseCandidate bestCollapse(const Mesh& mesh, const SimplifyStart& start, uint32_t edge);

// Step 2's result: the edges whose key (kNoCollapseKey: none) is the least of every vertex in
// their region, ascending.
std::vector<uint32_t> selectWinners(const Mesh& mesh, const VertexEdges& edges, const std::vector<uint64_t>& keys);

// Step 3's choice: keeps the winners with the least keys, as many as the target still needs
// (`vertices` are left) and at most 1/64 of the vertices, in key order.
void leastWinners(std::vector<uint32_t>& winners, const std::vector<uint64_t>& keys, uint32_t vertices,
                  uint32_t target);

// The cost a key holds: its double, cut.
double collapseKeyCost(uint64_t key);

// As simplifySerial, by the parallel rule.
ParallelSimplifyStats simplifyParallel(Mesh& mesh, Image& values, uint32_t target);

}  // namespace ddt
