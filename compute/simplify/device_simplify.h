// The parallel simplification rule (core/simplify/parallel_simplify.h) on a Vulkan device, in
// kernels of its own (glsl/simplify/), equal to core's bit for bit: every edge's best legal
// collapse (the legality walks, the exact orientation, the placement's solve and the
// quadric's value are the same formulas, in fp64 without fused multiply-add, and the key is a
// cut of the cost, not a rounding), the tally of the keys' cost words, the winners among the cheapest keys, whose
// regions hold no smaller tie word, and their collapses with the quadrics' merge. On the host:
// the cost limit from the tally, the round's least winners (a sort of the winners, downloaded
// each round), and the final compaction and best colours.
#pragma once

#include <string>
#include <vector>

#include "buffer.h"
#include "context.h"
#include "image.h"
#include "parallel_simplify.h"
#include "simplify_kernels.h"

namespace ddt {

// The device memory a DeviceSimplifier of a mesh with `edges` edges and `vertices` vertex ids
// allocates, and why the device cannot hold one ("" if it can).
uint64_t deviceSimplifierBytes(uint64_t edges, uint64_t vertices);
std::string deviceSimplifierProblem(const VulkanContext& context, uint64_t edges, uint64_t vertices);

// A winner of a selection: its edge and candidate.
struct DeviceWinner {
    uint32_t edge = kNone;
    CollapseCandidate candidate;
};


// A mesh being simplified on the device: its records, walk starts and quadrics live there.
class DeviceSimplifier {
public:
    // Uploads the mesh (its positions explicit), its walks' starts and quadrics in `start`, and the vertex values
    // `values` (what start.points reads); collapses beyond `max_error` are no candidates.
    DeviceSimplifier(VulkanContext& context, const Mesh& mesh, const SimplifyStart& start, const Image& values,
                     double max_error = 0.0);
    ~DeviceSimplifier();
    DeviceSimplifier(const DeviceSimplifier&) = delete;
    DeviceSimplifier& operator=(const DeviceSimplifier&) = delete;

    // Step 1 of a round on the current mesh: the candidates of the edges the last collapses
    // changed, and the tally of every key's cost word.
    void findCandidates();
    // Every edge's candidate (downloaded: for tests).
    std::vector<CollapseCandidate> candidates() const;
    // The keys per cost bin (core's costTally) at the last findCandidates.
    const std::vector<uint32_t>& costTally() const { return cost_tally_; }
    // Step 2 among the keys whose cost word is at most `limit`: the winners, in no order.
    std::vector<DeviceWinner> selectWinners(uint32_t cost_word_limit = kAllCostWords);
    // Step 3 for `collapses` (winners of one selection, in any order); one that moves goes to
    // its edge's candidate's target (of the last findCandidates).
    void collapse(const std::vector<Collapse>& collapses);
    // The current records, positions, walk starts and quadrics, into `mesh` and `start`.
    void download(Mesh& mesh, SimplifyStart& start) const;

private:
    // Lists the edges of gather_edges.comp's `step` after zeroing the tallies; their count.
    uint32_t gatherEdges(uint32_t step, uint32_t cost_word_limit);

    VulkanContext& context_;
    SimplifyKernels kernels_;
    Buffer buffers_[kSimplifyBindingCount];
    SimplifyPush push_{};
    std::vector<uint32_t> cost_tally_;  // keys per bin (kCostBins) at the last findCandidates
};

// As simplifyParallel, with steps 1 to 3 of every round on the device.
ParallelSimplifyStats simplifyOnDevice(VulkanContext& context, Mesh& mesh, Image& values, uint32_t target,
                                       double max_error = 0.0);

}  // namespace ddt
