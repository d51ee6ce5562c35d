// The resampling kernel (glsl/volume/tet_resample.comp, compute/volume/tet_resample_device.h)
// against core's resampler (core/volume/tet_resample.h), bit for bit: flipped meshes (with free
// slots), anisotropic sizes, magnification and minification per axis, ×1, samples on the box's
// high side and on faces, edges and vertices; the tets deferred to core by the int64 bound and
// by the loop budget; bricks' windows and small slabs. The validation layer and synchronization
// validation are on; each test requires zero messages.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "context.h"
#include "tet_lawson.h"
#include "tet_mesh.h"
#include "tet_parallel.h"
#include "tet_resample.h"
#include "tet_test_support.h"
#include "volume/tet_resample_device.h"
#include "volume_magnify.h"

using namespace ddt::test;

namespace {

std::unique_ptr<ddt::VulkanContext> validatedContext() { return ddt::createContext({-1, true}); }

size_t voxelCount(const Size& s) { return size_t(s[0]) * s[1] * s[2]; }

// The Kuhn mesh of `field` after the serial generalized Lawson: flipped tets, free slots.
ddt::TetMesh flippedMesh(const ddt::TetCostField& field) {
    ddt::TetMesh mesh = ddt::kuhnTetMesh(field.size);
    const ddt::TetLawsonStats stats = ddt::optimizeTetMeshSerial(mesh, field);
    REQUIRE(stats.flipCount() > 0);
    return mesh;
}

// Values that make every weight count: no two alike, none a simple fraction.
std::vector<float> valuesFor(const ddt::TetMesh& mesh) {
    std::vector<float> values(mesh.vertexCount());
    for (size_t v = 0; v < values.size(); ++v) values[v] = float(100.0 * std::sin(0.37 * double(v) + 0.1));
    return values;
}

// Bitwise equality of two outputs (NaN marks a voxel nobody wrote, and must match too); the
// number of voxels that differ.
size_t differentVoxels(const std::vector<float>& a, const std::vector<float>& b) {
    REQUIRE(a.size() == b.size());
    size_t different = 0;
    for (size_t i = 0; i < a.size(); ++i) different += std::memcmp(&a[i], &b[i], sizeof(float)) != 0;
    return different;
}

size_t nanVoxels(const std::vector<float>& values) {
    size_t nans = 0;
    for (float v : values) nans += std::isnan(v);
    return nans;
}

// The whole mesh resampled to new_size on the device (the output starts as NaN, as core's).
std::vector<float> deviceResample(ddt::VulkanContext& context, const ddt::TetMesh& mesh,
                                  const std::vector<float>& values, const Size& new_size,
                                  const ddt::TetResampleDeviceOptions& options = {},
                                  ddt::TetResampleDeviceReport* report = nullptr) {
    std::vector<float> out(voxelCount(new_size), std::numeric_limits<float>::quiet_NaN());
    const ddt::TetResampleWindow window{mesh.size, new_size, {0, 0, 0}, {0, 0, 0}, new_size};
    ddt::resampleTetsVulkan(context, mesh, values, window, out.data(), options, report);
    return out;
}

// Device against core on `mesh` at `new_size`; the device's report.
ddt::TetResampleDeviceReport compareWithCore(ddt::VulkanContext& context, const ddt::TetMesh& mesh,
                                             const Size& new_size, const ddt::TetResampleDeviceOptions& options = {}) {
    INFO(mesh.size[0] << "x" << mesh.size[1] << "x" << mesh.size[2] << " -> " << new_size[0] << "x" << new_size[1]
                      << "x" << new_size[2]);
    const std::vector<float> values = valuesFor(mesh);
    const std::vector<float> expected = ddt::resampleTets(mesh, values, new_size);
    ddt::TetResampleDeviceReport report;
    const std::vector<float> got = deviceResample(context, mesh, values, new_size, options, &report);
    CHECK(nanVoxels(expected) == 0);
    CHECK(differentVoxels(got, expected) == 0);
    return report;
}

}  // namespace

TEST_CASE("tet resample vulkan: flipped meshes at many factors equal core bit for bit", "[tet-resample-vulkan][vulkan]") {
    std::unique_ptr<ddt::VulkanContext> context = validatedContext();
    const ddt::TetMesh meshes[] = {flippedMesh(sphereField(7, 2.2)), flippedMesh(randomField({5, 3, 6}, 11, 3)),
                                   flippedMesh(slantedPlaneField(5, {1.0, 2.0, 0.5}))};
    for (const ddt::TetMesh& mesh : meshes) {
        REQUIRE(!mesh.free_slots.empty());  // the kernel must skip free slots
        const Size n = mesh.size;
        // ×2; ×1 (every sample on a vertex, the last on the high side); odd factors ×3 and ×5,
        // whose samples fall on faces, edges and vertices; mixed and per-axis factors;
        // minification, down to one voxel along an axis.
        const Size sizes[] = {{2 * n[0], 2 * n[1], 2 * n[2]}, n,
                              {3 * n[0], 3 * n[1], 3 * n[2]}, {5 * n[0], n[1], 3 * n[2]},
                              {2 * n[0] + 1, 3, 4 * n[2] - 1}, {n[0] / 2 + 1, 1, n[2] - 1},
                              {1, 1, 1}, {7, 2 * n[1] - 1, 2}};
        for (const Size& new_size : sizes) {
            const ddt::TetResampleDeviceReport report = compareWithCore(*context, mesh, new_size);
            CHECK(report.deferred == 0);  // nothing near the int64 bound or the loop budget
            CHECK(report.slabs == 1);
        }
    }
    CHECK(context->validation_messages == 0);
}

TEST_CASE("tet resample vulkan: x1 returns the input exactly, also on the device", "[tet-resample-vulkan][vulkan]") {
    std::unique_ptr<ddt::VulkanContext> context = validatedContext();
    const ddt::TetMesh mesh = flippedMesh(randomField({6, 4, 5}, 3, 4));
    const std::vector<float> values = valuesFor(mesh);
    CHECK(differentVoxels(deviceResample(*context, mesh, values, mesh.size), values) == 0);
    CHECK(context->validation_messages == 0);
}

TEST_CASE("tet resample vulkan: tets beyond the int64 bound go to core, by core's rule", "[tet-resample-vulkan][vulkan]") {
    std::unique_ptr<ddt::VulkanContext> context = validatedContext();
    const ddt::TetMesh mesh = flippedMesh(sphereField(7, 2.2));
    const Size new_size = {14, 9, 20};
    // The rule, on the host: a tet is deferred when 6 · Ex · Ey · Ez ≥ 2^L (Ea: its extent in the
    // exact units, 2m per voxel). At ×2 and more every tet's box holds samples, so every tet
    // meets the rule. L: the largest tets' bound, so that they are deferred and the rest not.
    std::vector<double> bounds;
    for (uint32_t t = 0; t < mesh.slotCount(); ++t) {
        if (!mesh.inUse(t)) continue;
        double bound = 6.0;
        for (int a = 0; a < 3; ++a) {
            uint32_t lo = UINT32_MAX, hi = 0;
            for (uint32_t id : mesh.vertices[t]) {
                const uint32_t c = a == 0 ? id % mesh.size[0] : a == 1 ? id / mesh.size[0] % mesh.size[1]
                                                                        : id / (mesh.size[0] * mesh.size[1]);
                lo = std::min(lo, c);
                hi = std::max(hi, c);
            }
            bound *= 2.0 * new_size[a] * (hi - lo);
        }
        bounds.push_back(bound);
    }
    const double largest = *std::max_element(bounds.begin(), bounds.end());
    const int log2 = int(std::floor(std::log2(largest)));
    const auto beyond = uint32_t(std::count_if(bounds.begin(), bounds.end(), [&](double b) { return b >= std::ldexp(1.0, log2); }));
    REQUIRE(beyond > 0);
    REQUIRE(beyond < mesh.tetCount());
    ddt::TetResampleDeviceOptions options;
    options.narrow_log2 = uint32_t(log2);
    CHECK(compareWithCore(*context, mesh, new_size, options).deferred == beyond);
    // Every tet beyond (the bound 2^0): core resamples them all, the same voxels.
    options.narrow_log2 = 0;
    CHECK(compareWithCore(*context, mesh, new_size, options).deferred == mesh.tetCount());
    CHECK(context->validation_messages == 0);
}

TEST_CASE("tet resample vulkan: tets whose box loops too long go to core", "[tet-resample-vulkan][vulkan]") {
    std::unique_ptr<ddt::VulkanContext> context = validatedContext();
    const ddt::TetMesh mesh = flippedMesh(randomField({5, 4, 4}, 7, 3));
    ddt::TetResampleDeviceOptions options;
    // At ×4 a Kuhn tet's box holds 4 · 4 · 4 samples in 16 rows (80 trips), a flipped tet's more.
    options.max_box_trips = 100;
    const ddt::TetResampleDeviceReport report = compareWithCore(*context, mesh, {20, 16, 16}, options);
    CHECK(report.deferred > 0);
    CHECK(report.deferred < mesh.tetCount());
    // The default budget keeps a Kuhn mesh's tets on the device up to about ×30
    // (tet_resample_layout.h); at ×20 a flipped tet two voxels wide along two axes is past it.
    CHECK(compareWithCore(*context, ddt::kuhnTetMesh(mesh.size), {100, 80, 80}).deferred == 0);
    const ddt::TetResampleDeviceReport x20 = compareWithCore(*context, mesh, {100, 80, 80});
    CHECK(x20.deferred > 0);
    CHECK(x20.deferred < mesh.tetCount());
    CHECK(context->validation_messages == 0);
}

TEST_CASE("tet resample vulkan: small slabs and bricks' windows equal core", "[tet-resample-vulkan][vulkan]") {
    std::unique_ptr<ddt::VulkanContext> context = validatedContext();
    const ddt::TetMesh mesh = flippedMesh(randomField({6, 5, 7}, 5, 3));
    // Slabs of whole planes, and of row runs within a plane (a plane of 13 × 11 > 40 voxels).
    for (uint64_t slab_voxels : {uint64_t(13 * 11 * 2), uint64_t(40), uint64_t(13)}) {
        INFO("slabs of " << slab_voxels << " voxels");
        ddt::TetResampleDeviceOptions options;
        options.slab_voxels = slab_voxels;
        CHECK(compareWithCore(*context, mesh, {13, 11, 15}, options).slabs > 1);
    }
    {
        ddt::TetResampleDeviceOptions options;
        options.slab_voxels = 12;  // shorter than a row of 13
        const ddt::TetResampleWindow window{mesh.size, {13, 11, 15}, {0, 0, 0}, {0, 0, 0}, {13, 11, 15}};
        CHECK(ddt::tetResampleDeviceProblem(*context, mesh, window, options) != "");
    }
    // Bricks (core/volume/volume_magnify.h): each brick's own flipped mesh, resampled into its
    // window of the whole output, by core and by the device.
    const Size size = {9, 7, 8}, new_size = {17, 15, 19};
    const ddt::TetCostField whole = randomField(size, 9, 3);
    std::vector<float> expected(voxelCount(new_size), std::numeric_limits<float>::quiet_NaN()), got = expected;
    const std::vector<ddt::VolumeBrick> bricks = ddt::volumeBricks(size, new_size, 4, 1);
    REQUIRE(bricks.size() > 1);
    for (const ddt::VolumeBrick& brick : bricks) {
        ddt::TetCostField field;
        field.size = brick.mesh_size;
        for (uint32_t z = 0; z < field.size[2]; ++z)
            for (uint32_t y = 0; y < field.size[1]; ++y)
                for (uint32_t x = 0; x < field.size[0]; ++x) {
                    const auto& o = brick.window.vertex_offset;
                    field.values.push_back(whole.values[(x + o[0]) + size[0] * ((y + o[1]) + size[1] * (z + o[2]))]);
                }
        ddt::TetMesh mesh = ddt::kuhnTetMesh(field.size);
        ddt::optimizeTetMeshSerial(mesh, field);
        const std::vector<float> values = valuesFor(mesh);
        ddt::resampleTetsInto(mesh, values, brick.window, expected.data());
        ddt::resampleTetsVulkan(*context, mesh, values, brick.window, got.data());
    }
    CHECK(nanVoxels(expected) == 0);
    CHECK(differentVoxels(got, expected) == 0);
    CHECK(context->validation_messages == 0);
}

TEST_CASE("tet resample vulkan: magnifyVolumeValues with the device's resampler equals core's", "[tet-resample-vulkan][vulkan]") {
    std::unique_ptr<ddt::VulkanContext> context = validatedContext();
    ddt::Volume volume;
    volume.size = {10, 9, 11};
    for (int a = 0; a < 3; ++a) volume.index_to_world.m[a][a] = 1.0;  // unit spacing
    const ddt::TetCostField field = randomField(volume.size, 21, 5);
    for (double v : field.values) volume.values.push_back(float(v * 250.0 - 40.0));
    for (uint32_t side : {0u, 5u}) {
        INFO("brick side " << side);
        ddt::VolumeMagnifyOptions options;
        options.brick_side = side;
        options.margin = 2;
        ddt::VolumeMagnifyStats stats;
        const std::vector<float> expected = ddt::magnifyVolumeValues(volume, {20, 27, 22}, options, stats);
        options.resample = [&](const ddt::TetMesh& mesh, const std::vector<float>& values,
                               const ddt::TetResampleWindow& window, float* out) {
            ddt::resampleTetsVulkan(*context, mesh, values, window, out);
        };
        const std::vector<float> got = ddt::magnifyVolumeValues(volume, {20, 27, 22}, options, stats);
        CHECK(stats.lawson.flipCount() > 0);
        CHECK(nanVoxels(expected) == 0);
        CHECK(differentVoxels(got, expected) == 0);
    }
    CHECK(context->validation_messages == 0);
}
