#include "stepwise_check.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "flip_gains.h"
#include "lawson.h"
#include "test_support.h"
#include "vulkan_backend.h"

namespace ddt::test {

double largestGain(const Mesh& mesh, const CostField& field, CostFunction cost) {
    double largest = -1.0;
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) largest = std::max(largest, flipGainOf(mesh, field, e, cost));
    return largest;
}

void checkVulkanStepwise(const Image& values, const Mesh& initial, CostFunction cost) {
    const CostField field = costFieldOf(values);
    VulkanOptions options;
    options.validation = true;
    options.cost = cost;
    VulkanBackend backend(options);
    backend.prepareFrom(values, initial);
    // The costs before any flip, edge by edge.
    const std::vector<double> device_costs = backend.deviceEdgeCosts();
    REQUIRE(device_costs.size() == initial.edgeCount());
    for (uint32_t e = 0; e < initial.edgeCount(); ++e)
        CHECK(std::abs(device_costs[e] - edgeCost(initial, field, e, cost)) <= kGainTolerance);
    Mesh expected_next = initial;
    uint32_t iterations = 0, flips = 0;
    backend.optimizeStepwise([&](const IterationSnapshot& snapshot) {
        ++iterations;
        // The device's mesh comes back with its positions.
        CHECK(sameRecords(snapshot.mesh, expected_next));
        // Each accepted gain, recomputed by core just before its own flip, is the device's.
        Mesh mesh = snapshot.mesh;
        for (uint32_t e : snapshot.accepted) {
            const size_t i = std::lower_bound(snapshot.candidates.begin(), snapshot.candidates.end(), e) -
                             snapshot.candidates.begin();
            REQUIRE(i < snapshot.candidates.size());
            CHECK(std::abs(flipGainOf(mesh, field, e, cost) - snapshot.candidate_gains[i]) <= kGainTolerance);
            flipEdge(mesh, e);
            ++flips;
        }
        CHECK(checkMesh(mesh, MeshHull::convex) == "");
        expected_next = std::move(mesh);
    });
    CHECK(iterations > 1);
    CHECK(flips > 0);
    const Mesh final_mesh = backend.mesh();
    CHECK(sameRecords(final_mesh, expected_next));
    CHECK(largestGain(final_mesh, field, cost) <= kFlipGainThreshold + kGainTolerance);
    CHECK(std::abs(backend.deviceMeshCost() - meshCost(final_mesh, field, cost)) <= 1e-9);
    CHECK(backend.validationMessages() == 0);
}

}  // namespace ddt::test
