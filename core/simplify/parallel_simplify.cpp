#include "parallel_simplify.h"

#include <algorithm>
#include <atomic>
#include <bit>

#include "parallel.h"
#include "placement.h"
#include "vertex_quadrics.h"

namespace ddt {

namespace {

// A round collapses at most 1/kRoundShare of the vertices left: more at once strays from the
// order of costs. Measured to 10 % of the vertices, with the merged vertex at an endpoint
// (before placement.h; PSNR of the render against the original; the serial reference: astronaut.png 37.08 dB, chelsea.png 36.46, coins.png 31.71):
//   1/16:  37.09 dB in 107 rounds, 36.43 in 55, 31.61 in 57;
//   1/32:  37.08 dB in 106 rounds, 36.43 in 77, 31.70 in 78;
//   1/64:  37.11 dB in 174 rounds, 36.45 in 148, 31.70 in 147;
//   1/128: 37.09 dB in 322 rounds, 36.44 in 295, 31.71 in 295.
constexpr uint32_t kRoundShare = 32;

// (cost, tieOrder(edge id)) in one ordered integer: the cost's double cut to its high 32
// bits (sign, exponent and 20 bits of mantissa, so costs within a relative 2^-20 tie and the
// lower tie word wins); a non-negative double's bits order as the double does. Cut, not
// rounded to float: Vulkan leaves the rounding of a double-to-float conversion to the
// implementation, a cut is exact on any device.
uint64_t keyOf(double cost, uint32_t edge) { return std::bit_cast<uint64_t>(cost) >> 32 << 32 | tieOrder(edge); }

// The vertices whose records and triangles a collapse of edge e reads or writes: its two
// vertices and all their neighbours.
template <typename Visit>
void forEachRegionVertex(const Mesh& mesh, const VertexEdges& edges, uint32_t e, Visit visit) {
    for (uint32_t v : {mesh.vertices[e].a, mesh.vertices[e].b}) {
        visit(v);
        forEachEdgeAt(mesh, edges, v, [&](uint32_t f) { visit(mesh.vertices[f].a == v ? mesh.vertices[f].b : mesh.vertices[f].a); });
    }
}

// A collapse of `from` changes the edges at `from` and at each of its neighbours (`to`
// among them), and no other record; it changes the quadric of `to` only, and, if it moves,
// `to`'s position. An edge's candidate reads only its own record, the edges at its two ends,
// their quadrics and the positions of the ends and their neighbours (canCollapse,
// placeCollapses), so only edges with an end marked here, for `from` before the collapse and
// for `to` after it if it moved, can have a new one.
void markRingChanged(const Mesh& mesh, const VertexEdges& edges, uint32_t v, std::vector<uint8_t>& changed) {
    changed[v] = 1;
    forEachEdgeAt(mesh, edges, v, [&](uint32_t f) { changed[mesh.vertices[f].a == v ? mesh.vertices[f].b : mesh.vertices[f].a] = 1; });
}

void lowerTo(std::atomic<uint64_t>& slot, uint64_t value) {
    uint64_t current = slot.load(std::memory_order_relaxed);
    while (value < current && !slot.compare_exchange_weak(current, value, std::memory_order_relaxed)) {
    }
}

}  // namespace

CollapseCandidate bestCollapse(const Mesh& mesh, const SimplifyStart& start, uint32_t edge, double error_limit) {
    CollapseCandidate best;
    if (removedEdge(mesh, edge)) return best;
    Quadric merged = start.quadrics[mesh.vertices[edge].a];
    merged += start.quadrics[mesh.vertices[edge].b];
    const std::array<PlacedCollapse, 2> placed = placeCollapses(mesh, start.edges, start.points, merged, edge);
    for (int direction : {1, 0}) {  // b into a first: it stays on equal keys
        const Collapse& collapse = placed[direction].collapse;
        if (!collapse.moves && !canCollapse(mesh, start.edges, collapse)) continue;  // a move is legal
        if (exceedsErrorLimit(placed[direction].cost, merged.area, error_limit)) continue;
        const uint64_t key = keyOf(placed[direction].cost, edge);
        if (key < best.key) best = {key, collapse.b_into_a, collapse.moves, collapse.target};
    }
    return best;
}

double collapseKeyCost(uint64_t key) { return std::bit_cast<double>(key >> 32 << 32); }

size_t roundCollapses(uint32_t vertices, uint32_t target) {
    return std::min<size_t>(vertices - target, std::max<size_t>(1, vertices / kRoundShare));
}

void leastWinners(std::vector<uint32_t>& winners, const std::vector<uint64_t>& keys, uint32_t vertices,
                  uint32_t target) {
    std::sort(winners.begin(), winners.end(), [&](uint32_t x, uint32_t y) { return keys[x] < keys[y]; });
    winners.resize(std::min(winners.size(), roundCollapses(vertices, target)));
}

std::vector<uint32_t> costTally(const std::vector<uint64_t>& keys) {
    std::vector<uint32_t> tally(kCostBins, 0);
    for (uint64_t key : keys)
        if (key != kNoCollapseKey) ++tally[costBin(uint32_t(key >> 32))];
    return tally;
}

uint32_t costWordLimit(const std::vector<uint32_t>& tally, size_t count) {
    uint64_t total = 0, keys = 0;
    for (uint32_t keys_in_bin : tally) total += keys_in_bin;
    for (uint32_t bin = 0; bin + 1 < kCostBins; ++bin) {
        keys += tally[bin];
        if (keys == total) break;
        if (keys >= count) return bin << 16 | 0xFFFFu;
    }
    return kAllCostWords;
}

std::vector<uint32_t> selectWinners(const Mesh& mesh, const VertexEdges& edges, const std::vector<uint64_t>& keys,
                                    uint32_t limit) {
    const size_t grain = 4096, edge_count = mesh.edgeCount(), vertex_count = mesh.vertexCount();
    enum : uint8_t { kUndecided, kWon, kOut };
    std::vector<uint8_t> state(edge_count), taken(vertex_count, 0);
    parallelFor(edge_count, grain, [&](size_t begin, size_t end) {
        for (size_t e = begin; e < end; ++e)
            state[e] = keys[e] != kNoCollapseKey && uint32_t(keys[e] >> 32) <= limit ? kUndecided : kOut;
    });
    std::vector<std::atomic<uint64_t>> vertex_least(vertex_count);
    std::vector<uint32_t> winners;
    for (uint32_t pass = 0; pass < kSelectionPasses; ++pass) {
        // Each vertex's least key over the undecided regions that hold it.
        parallelFor(vertex_count, grain, [&](size_t begin, size_t end) {
            for (size_t v = begin; v < end; ++v) vertex_least[v].store(kNoCollapseKey, std::memory_order_relaxed);
        });
        parallelFor(edge_count, grain, [&](size_t begin, size_t end) {
            for (size_t e = begin; e < end; ++e)
                if (state[e] == kUndecided)
                    forEachRegionVertex(mesh, edges, uint32_t(e), [&](uint32_t v) { lowerTo(vertex_least[v], keys[e]); });
        });
        const size_t earlier = winners.size();
        for (uint32_t e = 0; e < edge_count; ++e) {
            if (state[e] != kUndecided) continue;
            bool least = true;
            forEachRegionVertex(mesh, edges, e, [&](uint32_t v) { least = least && vertex_least[v].load() == keys[e]; });
            if (least) winners.push_back(e);
        }
        for (size_t i = earlier; i < winners.size(); ++i) {
            state[winners[i]] = kWon;
            forEachRegionVertex(mesh, edges, winners[i], [&](uint32_t v) { taken[v] = 1; });
        }
        // Out: the undecided whose region touches a winner's.
        parallelFor(edge_count, grain, [&](size_t begin, size_t end) {
            for (size_t e = begin; e < end; ++e) {
                if (state[e] != kUndecided) continue;
                bool touches = false;
                forEachRegionVertex(mesh, edges, uint32_t(e), [&](uint32_t v) { touches = touches || taken[v]; });
                if (touches) state[e] = kOut;
            }
        });
    }
    std::sort(winners.begin(), winners.end());
    return winners;
}

ParallelSimplifyStats simplifyParallel(Mesh& mesh, Image& values, uint32_t target, double max_error) {
    ParallelSimplifyStats stats;
    stats.vertices_before = stats.vertices_after = usedVertexCount(mesh);
    makePositionsExplicit(mesh);
    SimplifyStart start(mesh, values);
    auto& [points, quadrics, edges, samples] = start;
    const uint32_t edge_count = mesh.edgeCount();
    const double error_limit = errorLimitOf(max_error);
    std::vector<uint64_t> key(edge_count);
    std::vector<CollapseCandidate> candidates(edge_count);
    // The vertices whose edges the last round's collapses changed (markRingChanged); an edge
    // with neither end among them keeps its candidate (all are new at first).
    std::vector<uint8_t> changed(mesh.vertexCount(), 1);
    const size_t grain = 4096;

    while (stats.vertices_after > target) {
        // 1. Candidates: each edge's best legal collapse.
        parallelFor(edge_count, grain, [&](size_t begin, size_t end) {
            for (size_t e = begin; e < end; ++e) {
                if (removedEdge(mesh, uint32_t(e))) {
                    key[e] = kNoCollapseKey;
                    continue;
                }
                if (!changed[mesh.vertices[e].a] && !changed[mesh.vertices[e].b]) continue;
                candidates[e] = bestCollapse(mesh, start, uint32_t(e), error_limit);
                key[e] = candidates[e].key;
            }
        });
        // 2. Select, and keep the least winners, as many as the target still needs.
        const size_t needed = roundCollapses(stats.vertices_after, target);
        std::vector<uint32_t> winners =
            selectWinners(mesh, edges, key, costWordLimit(costTally(key), kKeysPerCollapse * needed));
        leastWinners(winners, key, stats.vertices_after, target);
        if (winners.empty()) break;  // no legal collapse left
        // 3. Collapse them.
        std::fill(changed.begin(), changed.end(), 0);
        for (uint32_t e : winners) {
            const Collapse collapse{e, candidates[e].b_into_a, candidates[e].moves, candidates[e].target};
            const uint32_t from = collapse.from(mesh), to = collapse.to(mesh);
            markRingChanged(mesh, edges, from, changed);
            stats.last_cost = std::max(stats.last_cost, collapseKeyCost(key[e]));
            collapseEdge(mesh, edges, collapse);
            quadrics[to] += quadrics[from];
            if (collapse.moves) markRingChanged(mesh, edges, to, changed);
        }
        stats.collapses += winners.size();
        stats.vertices_after -= uint32_t(winners.size());
        ++stats.rounds;
    }
    compactEdges(mesh);
    setVertexColours(mesh, start, values);
    return stats;
}

}  // namespace ddt
