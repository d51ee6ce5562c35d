// The parallel flip rule's kernels (glsl/volume/, compute/volume/tet_device.h) against core's
// rule (core/volume/tet_parallel.h), bit for bit: every slot's vertices and neighbours, the free
// slots in order, the statistics, every cached cost and the totals. The validation layer and
// synchronization validation are on; each test requires zero messages.
#include <catch2/catch.hpp>

#include <array>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "tet_test_support.h"
#include "context.h"
#include "tet_cost.h"
#include "tet_mesh.h"
#include "tet_parallel.h"
#include "volume/tet_device.h"

using ddt::TetWeight;

using namespace ddt::test;

namespace {

// Bitwise equality of doubles (0.0 and −0.0 differ, as a bit-for-bit claim should).
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

std::unique_ptr<ddt::VulkanContext> validatedContext() { return ddt::createContext({-1, true}); }

// Runs core's rule and the device's on `start` (the Kuhn mesh of `field` by default) and
// compares everything; the device's report.
ddt::TetDeviceReport compareWithCore(ddt::VulkanContext& context, const ddt::TetCostField& field, TetWeight weight,
                                     uint32_t max_rounds = 100000, ddt::TetDeviceOptions device = {},
                                     const ddt::TetMesh* start = nullptr) {
    INFO(ddt::tetWeightName(weight) << ", at most " << max_rounds << " rounds, " << device.rounds_per_submit
                                    << " rounds a submit, slack " << device.slack);
    ddt::TetParallelOptions options;
    options.weight = weight;
    options.max_rounds = max_rounds;
    ddt::TetMesh cpu = start ? *start : ddt::kuhnTetMesh(field.size), gpu = cpu;
    const ddt::TetParallelStats expected = ddt::optimizeTetMeshParallel(cpu, field, options);
    ddt::TetDeviceReport report;
    const ddt::TetParallelStats got = ddt::optimizeTetMeshVulkan(context, gpu, field, options, device, &report);
    CHECK(ddt::checkTetMesh(gpu) == "");
    CHECK(gpu.slotCount() == cpu.slotCount());
    CHECK(gpu.vertices == cpu.vertices);
    CHECK(gpu.neighbours == cpu.neighbours);
    CHECK(gpu.free_slots == cpu.free_slots);
    CHECK(got.flips == expected.flips);
    CHECK(got.rounds == expected.rounds);
    CHECK(got.capped == expected.capped);
    CHECK(got.evaluated == expected.evaluated);
    CHECK(got.candidates == expected.candidates);
    CHECK(sameBits(got.cost_before, expected.cost_before));
    CHECK(sameBits(got.cost_after, expected.cost_after));
    // Every slot's cached cost, against core's cache of the same mesh.
    const ddt::TetCosts costs(cpu, field, weight);
    REQUIRE(report.costs.size() == cpu.slotCount());
    uint32_t different = 0;
    for (uint32_t t = 0; t < cpu.slotCount(); ++t) different += !sameBits(report.costs[t], costs.cost(t));
    CHECK(different == 0);
    CHECK(report.capacity >= gpu.slotCount());
    return report;
}

// The mesh optimized for one random field, compacted (no free slots): optimized again for
// another field (randomField({7, 6, 5}, 2, 1000)), its first rounds append slots.
ddt::TetMesh compactedMeshOfAnotherField() {
    ddt::TetParallelOptions options;
    options.weight = TetWeight::variance;
    const ddt::TetCostField first = randomField({7, 6, 5}, 1, 1000);
    ddt::TetMesh mesh = ddt::kuhnTetMesh(first.size);
    ddt::optimizeTetMeshParallel(mesh, first, options);
    return compacted(mesh);
}

}  // namespace

TEST_CASE("tet vulkan: a sphere and a slanted plane equal core's parallel rule bit for bit", "[tet-vulkan][vulkan]") {
    std::unique_ptr<ddt::VulkanContext> context = validatedContext();
    for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
        compareWithCore(*context, sphereField(9, 3.0), weight);
        compareWithCore(*context, slantedPlaneField(8, {0.8, 0.8, 2.0}), weight);
    }
    CHECK(context->validation_messages == 0);
}

TEST_CASE("tet vulkan: random values, round by round: many 2-3 and 3-2 flips take and free slots alike", "[tet-vulkan][vulkan]") {
    std::unique_ptr<ddt::VulkanContext> context = validatedContext();
    const ddt::TetCostField field = randomField({7, 6, 5}, 11, 1000);
    for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
        for (uint32_t rounds : {1u, 2u, 3u, 5u}) compareWithCore(*context, field, weight, rounds);
        compareWithCore(*context, field, weight);
        compareWithCore(*context, field, weight, 100000, {1, 0.25});  // one round a submit
    }
    // Few levels: many equal gains, decided by the tie words.
    const ddt::TetCostField ties = randomField({6, 6, 6}, 5, 3);
    for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) compareWithCore(*context, ties, weight);
    CHECK(context->validation_messages == 0);
}

TEST_CASE("tet vulkan: slots appended beyond the arrays: they grow mid-round to the same result", "[tet-vulkan][vulkan]") {
    // The mesh of one random field, compacted (no free slots), optimized for another: its first
    // rounds append slots. With no slack the arrays must grow, in the middle of a round.
    std::unique_ptr<ddt::VulkanContext> context = validatedContext();
    const ddt::TetCostField second = randomField({7, 6, 5}, 2, 1000);
    ddt::TetMesh mesh = compactedMeshOfAnotherField();
    for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
        const ddt::TetDeviceReport tight = compareWithCore(*context, second, weight, 100000, {4, 0.0}, &mesh);
        if (weight == TetWeight::variance) CHECK(tight.grows > 0);
        const ddt::TetDeviceReport roomy = compareWithCore(*context, second, weight, 100000, {}, &mesh);
        CHECK(roomy.grows == 0);
    }
    CHECK(context->validation_messages == 0);
}

// The memory lever for lavapipe, whose device memory is host memory: only what the kernels read
// before they write is zeroed (a fill makes every page of its range resident), so the spare
// slots, the lists' unused tails and the claims of slots no candidate reads never become
// resident. What is zeroed, counted here from the layout: the state word (4 bytes) of each slot
// in use, and the scan words, per block of 32 768 slots of capacity 1 024 pairs of mask words
// (8 bytes), 1 024 pairs of prefixes (8 bytes) and the block's totals (16 bytes). A generous
// slack (capacity 4 × the slots) makes zeroing the whole capacity, or the claims, show: the
// state words alone would be 4 times as many bytes.
TEST_CASE("tet vulkan: only the arrays read before written are zeroed", "[tet-vulkan][vulkan]") {
    std::unique_ptr<ddt::VulkanContext> context = validatedContext();
    const ddt::TetCostField field = sphereField(9, 3.0);
    const uint64_t slots = ddt::kuhnTetMesh(field.size).slotCount();
    const ddt::TetDeviceReport report = compareWithCore(*context, field, TetWeight::variance, 100000, {16, 3.0});
    REQUIRE(report.grows == 0);
    REQUIRE(report.capacity >= 4 * slots);
    const uint64_t blocks = (report.capacity + 32767) / 32768;
    CHECK(report.zeroed_bytes == 4 * slots + blocks * (1024 * 8 + 1024 * 8 + 16));
    CHECK(context->validation_messages == 0);
}

// What is not zeroed must be written before it is read: with every array filled with 1 bits
// first (no valid state word: every slot would look listed; every claim would look taken), the
// result is still core's, with and without growth (a growth's new arrays are filled too).
TEST_CASE("tet vulkan: arrays full of garbage at the start change nothing", "[tet-vulkan][vulkan]") {
    std::unique_ptr<ddt::VulkanContext> context = validatedContext();
    ddt::TetDeviceOptions poisoned;
    poisoned.poison = true;
    for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
        compareWithCore(*context, sphereField(9, 3.0), weight, 100000, poisoned);
        compareWithCore(*context, randomField({7, 6, 5}, 11, 1000), weight, 100000, poisoned);
    }
    // Slots appended at once and after growths (no slack), as in the growth test above.
    const ddt::TetCostField second = randomField({7, 6, 5}, 2, 1000);
    ddt::TetMesh mesh = compactedMeshOfAnotherField();
    poisoned.slack = 0.0;
    CHECK(compareWithCore(*context, second, TetWeight::variance, 100000, poisoned, &mesh).grows > 0);
    CHECK(context->validation_messages == 0);
}

// The app's way: the field taken (its values released once uploaded) and the mesh back without
// its neighbours; the same vertices and free slots as with both.
TEST_CASE("tet vulkan: a taken field and the mesh back without its neighbours", "[tet-vulkan][vulkan]") {
    std::unique_ptr<ddt::VulkanContext> context = validatedContext();
    const ddt::TetCostField field = sphereField(9, 3.0);
    ddt::TetParallelOptions options;
    options.weight = TetWeight::variance;
    ddt::TetMesh whole = ddt::kuhnTetMesh(field.size), bare = whole;
    const ddt::TetParallelStats expected = ddt::optimizeTetMeshVulkan(*context, whole, field, options);
    ddt::TetCostField taken = field;
    ddt::TetDeviceOptions device;
    device.return_neighbours = false;
    const ddt::TetParallelStats got = ddt::optimizeTetMeshVulkan(*context, bare, std::move(taken), options, device);
    CHECK(taken.values.empty());
    CHECK(bare.neighbours.empty());
    CHECK(bare.vertices == whole.vertices);
    CHECK(bare.free_slots == whole.free_slots);
    CHECK(got.flips == expected.flips);
    CHECK(sameBits(got.cost_after, expected.cost_after));
    CHECK(context->validation_messages == 0);
}

TEST_CASE("tet vulkan: a flat volume and a mesh with free slots", "[tet-vulkan][vulkan]") {
    std::unique_ptr<ddt::VulkanContext> context = validatedContext();
    const ddt::TetCostField flat = fieldOf({4, 3, 5}, [](uint32_t, uint32_t, uint32_t) { return 7.0; });
    for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) compareWithCore(*context, flat, weight);

    // A mesh that already has free slots (after core's rule on other values) goes on from there.
    const ddt::TetCostField first = randomField({6, 5, 5}, 21, 100), second = randomField({6, 5, 5}, 22, 100);
    for (TetWeight weight : {TetWeight::variance, TetWeight::face_scf}) {
        ddt::TetParallelOptions options;
        options.weight = weight;
        ddt::TetMesh cpu = ddt::kuhnTetMesh(first.size);
        ddt::optimizeTetMeshParallel(cpu, first, options);
        REQUIRE_FALSE(cpu.free_slots.empty());
        ddt::TetMesh gpu = cpu;
        const ddt::TetParallelStats expected = ddt::optimizeTetMeshParallel(cpu, second, options);
        const ddt::TetParallelStats got = ddt::optimizeTetMeshVulkan(*context, gpu, second, options);
        CHECK(gpu.vertices == cpu.vertices);
        CHECK(gpu.neighbours == cpu.neighbours);
        CHECK(gpu.free_slots == cpu.free_slots);
        CHECK(got.flips == expected.flips);
        CHECK(sameBits(got.cost_after, expected.cost_after));
    }
    CHECK(context->validation_messages == 0);
}
