// The Vulkan backend on lavapipe, checked against core (the serial reference) and against
// itself. Every backend here runs with the Khronos validation layer and synchronization
// validation; each test requires zero validation messages.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>

#include "cost.h"
#include "flip_rule.h"
#include "lawson.h"
#include "mesh.h"
#include "render.h"
#include "test_support.h"
#include "context.h"
#include "layout.h"
#include "vulkan_backend.h"
#include "image_file.h"

namespace {

using namespace ddt;

// Gains are computed in fp64 by the same code (glsl/image/sederberg.h) on both sides, but a
// device may round division and square root differently in the last bit; a gain sums ten
// terms below ~8, so such differences stay far below 1e-12.
const double kGainTolerance = 1e-12;

// Seeded random images from the shared test helpers (levels > 0: few values, many ties).
Image randomImage(uint32_t width, uint32_t height, uint32_t channels, uint32_t seed, uint32_t levels = 0) {
    std::mt19937 rng(seed);
    return test::randomImage(rng, width, height, channels, levels);
}

Image fixture(const char* name) { return readImage(test::testDataPath(name)); }

struct TestImage {
    const char* label;
    Image image;
};

std::vector<TestImage> testImages() {
    return {{"random RGB 13x9", randomImage(13, 9, 3, 1)},
            {"random grey 24x17", randomImage(24, 17, 1, 2)},
            {"four-level grey 20x20", randomImage(20, 20, 1, 3, 4)},
            {"random RGBA 11x14", randomImage(11, 14, 4, 4)},
            {"astronaut crop 32x32", fixture("crop32_astronaut.png")}};
}

VulkanBackend makeBackend(const std::string& rule, bool active_set = true, bool profile = false) {
    VulkanOptions options;
    options.rule = rule;
    options.active_set = active_set;
    options.validation = true;
    options.profile = profile;
    return VulkanBackend(options);
}

double largestGain(const Mesh& mesh, const CostField& field) {
    double largest = -1.0;
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) largest = std::max(largest, flipGainOf(mesh, field, e));
    return largest;
}

}  // namespace

TEST_CASE("vulkan: every rule yields a valid, locally optimal mesh", "[vulkan]") {
    const std::vector<TestImage> images = testImages();
    for (const std::string& rule : tableFlipRules()) {
        VulkanBackend backend = makeBackend(rule);
        for (const TestImage& test : images) {
            INFO(rule << " on " << test.label);
            backend.prepare(test.image);
            const OptimizeStats stats = backend.optimize();
            const Mesh mesh = backend.mesh();
            const CostField field = costFieldOf(test.image);
            CHECK(checkMesh(mesh) == "");
            CHECK_FALSE(stats.capped);
            CHECK(largestGain(mesh, field) <= kFlipGainThreshold + kGainTolerance);
            CHECK(stats.flips > 0);
            CHECK(stats.cost_final < stats.cost_init);
            // The device's cost sums agree with core's on both meshes (summation order differs).
            CHECK(stats.cost_init == Approx(meshCost(buildGridMesh(test.image.width, test.image.height), field)).epsilon(1e-12));
            CHECK(stats.cost_final == Approx(meshCost(mesh, field)).epsilon(1e-12));
        }
        CHECK(backend.validationMessages() == 0);
    }
}

TEST_CASE("vulkan: the kernels' edge costs equal core's", "[vulkan]") {
    VulkanBackend backend = makeBackend("localmax");
    for (const TestImage& test : testImages()) {
        INFO(test.label);
        backend.prepare(test.image);
        backend.optimize();  // compare on an optimised mesh, where flipped edges are long and slanted
        const Mesh mesh = backend.mesh();
        const CostField field = costFieldOf(test.image);
        const std::vector<double> device_costs = backend.deviceEdgeCosts();
        double worst = 0.0;
        for (uint32_t e = 0; e < mesh.edgeCount(); ++e)
            worst = std::max(worst, std::abs(device_costs[e] - edgeCost(mesh, field, e)));
        // Same formula and operation order, contraction forbidden: only a last-bit difference
        // in the device's division or square root could remain (costs are below ~8).
        CHECK(worst <= 1e-14);
    }
    CHECK(backend.validationMessages() == 0);
}

TEST_CASE("vulkan: accepted edges are never in each other's ROI, and their gains are exact", "[vulkan]") {
    const std::vector<TestImage> images = testImages();
    for (const char* rule : {"basic", "exproi", "maxgain", "exproi2-maxgain", "localmax"}) {
        const FlipRule flip_rule = *parseFlipRule(rule);
        VulkanBackend backend = makeBackend(rule);
        for (const TestImage& test : images) {
            INFO(rule << " on " << test.label);
            backend.prepare(test.image);
            const CostField field = costFieldOf(test.image);
            Mesh expected_next;  // the previous iteration's mesh with its flips applied on the host
            uint32_t iterations = 0;
            uint64_t accepted_edges = 0;
            const OptimizeStats stats = backend.optimizeStepwise([&](const IterationSnapshot& snapshot) {
                ++iterations;
                accepted_edges += snapshot.accepted.size();
                if (snapshot.iteration > 0) CHECK(test::sameRecords(snapshot.mesh, expected_next));
                const int degree = snapshot.iteration < flip_rule.exproi_iterations ? 3 : 2;
                const std::vector<uint32_t>& accepted = snapshot.accepted;
                REQUIRE_FALSE(accepted.empty());
                for (uint32_t e : accepted)
                    for (uint32_t f : regionOf(snapshot.mesh, e, degree))
                        CHECK_FALSE(std::binary_search(accepted.begin(), accepted.end(), f));

                // Flip the accepted edges one after another on the host: each gain, recomputed
                // just before its own flip, equals the candidate step's, so the cost falls by
                // their sum.
                Mesh mesh = snapshot.mesh;
                double gain_sum = 0.0;
                const double cost_before = meshCost(mesh, field);
                for (uint32_t e : accepted) {
                    const size_t i = std::lower_bound(snapshot.candidates.begin(), snapshot.candidates.end(), e) -
                                     snapshot.candidates.begin();
                    CHECK(std::abs(flipGainOf(mesh, field, e) - snapshot.candidate_gains[i]) <= kGainTolerance);
                    gain_sum += snapshot.candidate_gains[i];
                    flipEdge(mesh, e);
                }
                // Summation order differs between the two sides: relative 1e-12 of the total.
                CHECK(meshCost(mesh, field) == Approx(cost_before - gain_sum).epsilon(1e-12).margin(1e-12));
                CHECK(checkMesh(mesh) == "");
                expected_next = std::move(mesh);
            });
            CHECK(iterations > 0);
            CHECK(test::sameRecords(backend.mesh(), expected_next));
            // The flips counted as select lists them for flip.comp: each accepted edge once.
            CHECK(stats.flips == accepted_edges);
        }
        CHECK(backend.validationMessages() == 0);
    }
}

TEST_CASE("vulkan: local-max accepts exactly the candidates that beat every candidate in their ROI", "[vulkan]") {
    // Its one round (glsl/image/select.comp) against the rule checked on the host over the
    // whole 2-region: the larger gain wins, equal gains by the lower id.
    VulkanBackend backend = makeBackend("localmax");
    for (const TestImage& test : testImages()) {
        INFO(test.label);
        backend.prepare(test.image);
        uint32_t iterations = 0;
        backend.optimizeStepwise([&](const IterationSnapshot& snapshot) {
            ++iterations;
            const std::vector<uint32_t>& candidates = snapshot.candidates;  // sorted, gains alongside
            auto gainOf = [&](uint32_t f) {
                return snapshot.candidate_gains[std::lower_bound(candidates.begin(), candidates.end(), f) -
                                                candidates.begin()];
            };
            std::vector<uint32_t> expected;
            for (uint32_t e : candidates) {
                bool best = true;
                for (uint32_t f : regionOf(snapshot.mesh, e, 2))
                    if (f != e && std::binary_search(candidates.begin(), candidates.end(), f))
                        best = best && (gainOf(e) > gainOf(f) || (gainOf(e) == gainOf(f) && e < f));
                if (best) expected.push_back(e);
            }
            CHECK(snapshot.accepted == expected);
            CHECK(snapshot.accepted.size() + snapshot.undecided.size() == candidates.size());
        });
        CHECK(iterations > 1);
    }
    CHECK(backend.validationMessages() == 0);
}

TEST_CASE("vulkan: the active set changes nothing but the work", "[vulkan]") {
    const std::vector<TestImage> images = testImages();
    for (const std::string& rule : tableFlipRules()) {
        VulkanBackend with = makeBackend(rule, true);
        VulkanBackend without = makeBackend(rule, false);
        for (const TestImage& test : images) {
            INFO(rule << " on " << test.label);
            with.prepare(test.image);
            without.prepare(test.image);
            const OptimizeStats a = with.optimize();
            const OptimizeStats b = without.optimize();
            CHECK(test::sameRecords(with.mesh(), without.mesh()));
            CHECK(a.flips == b.flips);
            CHECK(a.iterations == b.iterations);
            CHECK(a.rounds == b.rounds);
        }
        CHECK(with.validationMessages() == 0);
        CHECK(without.validationMessages() == 0);
    }
}

TEST_CASE("vulkan: batched submits give the mesh of one step per submit", "[vulkan]") {
    // optimize() records many iterations and rounds per submit and lets the device's plan
    // kernel skip what is not needed; iterations that need more rounds than a submit holds
    // continue in the next one. The result must equal stepping one round at a time.
    const std::vector<TestImage> images = testImages();
    for (const std::string& rule : tableFlipRules()) {
        VulkanBackend batched = makeBackend(rule);
        VulkanBackend stepped = makeBackend(rule);
        for (const TestImage& test : images) {
            INFO(rule << " on " << test.label);
            batched.prepare(test.image);
            stepped.prepare(test.image);
            const OptimizeStats a = batched.optimize();
            const OptimizeStats b = stepped.optimizeStepwise([](const IterationSnapshot&) {});
            CHECK(test::sameRecords(batched.mesh(), stepped.mesh()));
            CHECK(a.flips == b.flips);
            CHECK(a.rounds == b.rounds);
            CHECK(a.iterations == b.iterations);
        }
        CHECK(batched.validationMessages() == 0);
    }
}

TEST_CASE("vulkan: ExpROI with N = 0 is basic", "[vulkan]") {
    VulkanBackend basic = makeBackend("basic");
    VulkanBackend exproi0 = makeBackend("exproi-0-maxgain");
    VulkanBackend maxgain = makeBackend("maxgain");
    VulkanBackend exproi0_basic = makeBackend("exproi0");
    for (const TestImage& test : testImages()) {
        INFO(test.label);
        for (VulkanBackend* b : {&basic, &exproi0, &maxgain, &exproi0_basic}) {
            b->prepare(test.image);
            b->optimize();
        }
        CHECK(test::sameRecords(basic.mesh(), exproi0_basic.mesh()));
        CHECK(test::sameRecords(maxgain.mesh(), exproi0.mesh()));
    }
}

// Two candidates in each other's ROI, the one with the larger id having the larger gain.
// A 4×4 grey image, white but for a black and a grey pixel:
//
//        x=0   x=1   x=2   x=3
//   y=0   1     1     1     1
//   y=1   1     0     1     1        e = edge 12, the diagonal (0,1)–(1,2)
//   y=2   1    0.5    1     1        f = edge 23, the row edge (1,2)–(2,2)
//   y=3   1     1     1     1
//
//   (0,1)      (1,1)                 Both want to flip; f lies in e's 2-region (both
//     +---------+                    touch the grey vertex (1,2)), so at most one of them
//     |  \   e  |                    flips in the first iteration.
//     |     \   |
//     +---------+---------+
//   (0,2)    (1,2)   f    (2,2)
TEST_CASE("vulkan: MaxGain and local-max prefer the larger gain over the lower id", "[vulkan]") {
    Image image;
    image.width = 4;
    image.height = 4;
    image.channels = 1;
    image.pixels.assign(16, 1.0f);
    image.pixels[1 * 4 + 1] = 0.0f;
    image.pixels[2 * 4 + 1] = 0.5f;
    const uint32_t e = 12, f = 23;

    // The premise, from the serial reference: exactly these two candidates, in conflict.
    const Mesh grid = buildGridMesh(4, 4);
    const CostField field = costFieldOf(image);
    for (uint32_t g = 0; g < grid.edgeCount(); ++g)
        CHECK((flipGainOf(grid, field, g) > kFlipGainThreshold) == (g == e || g == f));
    const std::vector<uint32_t> roi = regionOf(grid, e, 2);
    REQUIRE(std::find(roi.begin(), roi.end(), f) != roi.end());
    REQUIRE(flipGainOf(grid, field, f) > flipGainOf(grid, field, e));

    auto first_iteration = [&](const std::string& rule) {
        VulkanBackend backend = makeBackend(rule);
        backend.prepare(image);
        IterationSnapshot first;
        backend.optimizeStepwise([&](const IterationSnapshot& s) {
            if (s.iteration == 0) first = s;
        });
        CHECK(backend.validationMessages() == 0);
        return first;
    };
    const IterationSnapshot basic = first_iteration("basic");
    CHECK(basic.accepted == std::vector<uint32_t>{e});  // lowest id wins
    const IterationSnapshot maxgain = first_iteration("maxgain");
    CHECK(maxgain.accepted == std::vector<uint32_t>{f});  // larger gain wins, e rejected
    CHECK(maxgain.undecided.empty());
    const IterationSnapshot localmax = first_iteration("localmax");
    CHECK(localmax.accepted == std::vector<uint32_t>{f});
    CHECK(localmax.undecided == std::vector<uint32_t>{e});  // left for the next iteration, not rejected
    CHECK(localmax.rounds == 1);
}

TEST_CASE("vulkan: results are the same on every run and with one or two lavapipe threads", "[heavy][vulkan]") {
    const Image image = fixture("crop32_astronaut.png");
    const OutputSize out = scaledOutputSize(image.width, image.height, 2.5);
    const char* saved = std::getenv("LP_NUM_THREADS");
    const std::string restore = saved ? saved : "";
    for (const std::string& rule : tableFlipRules()) {
        INFO(rule);
        std::vector<Mesh> meshes;
        std::vector<std::vector<float>> renders;
        for (const char* threads : {"2", "1", "2"}) {
            setenv("LP_NUM_THREADS", threads, 1);  // read when the device is created
            VulkanBackend backend = makeBackend(rule);
            backend.prepare(image);
            backend.optimize();
            meshes.push_back(backend.mesh());
            std::vector<float> rows(size_t(out.width) * out.height * image.channels);
            backend.renderRows(out, 0, out.height, rows.data());
            renders.push_back(std::move(rows));
        }
        for (size_t i = 1; i < meshes.size(); ++i) {
            CHECK(test::sameRecords(meshes[0], meshes[i]));
            CHECK(renders[0] == renders[i]);
        }
    }
    if (saved) setenv("LP_NUM_THREADS", restore.c_str(), 1);
    else unsetenv("LP_NUM_THREADS");
}

// Rows the device rendered into a NaN-filled buffer, against core's rendering of the same
// mesh: every pixel written, and equal up to the interpolation's rounding. The device weighs
// in float, core in double: at most 1.2e-7 apart on lavapipe (measured on these tests); 1e-5
// leaves room for a GPU's fused multiply-adds and is still far inside one 8-bit level.
static void checkMatchesCore(const std::vector<float>& rows, const Image& reference) {
    REQUIRE(rows.size() == reference.pixels.size());
    CHECK(std::all_of(rows.begin(), rows.end(), [](float v) { return std::isfinite(v); }));
    double worst = 0.0;
    for (size_t i = 0; i < rows.size(); ++i) worst = std::max(worst, double(std::abs(rows[i] - reference.pixels[i])));
    CHECK(worst <= 1e-5);
}

TEST_CASE("vulkan: the device renderer matches core's on the same mesh", "[vulkan]") {
    struct Case {
        Image image;
        double scale;
    };
    const std::vector<Case> cases = {{randomImage(13, 9, 3, 5), 1.0},  {randomImage(13, 9, 3, 5), 2.5},
                                     {randomImage(7, 12, 1, 6), 3.0},  {randomImage(9, 9, 2, 7), 8.0},
                                     {randomImage(10, 6, 4, 8), 2.0},  {fixture("crop32_astronaut.png"), 7.3}};
    VulkanBackend backend = makeBackend("localmax");
    for (const Case& c : cases) {
        INFO(c.image.width << "x" << c.image.height << "x" << c.image.channels << " scaled " << c.scale);
        backend.prepare(c.image);
        backend.optimize();
        const Mesh mesh = backend.mesh();
        const OutputSize out = scaledOutputSize(c.image.width, c.image.height, c.scale);
        const Image reference = renderImage(mesh, c.image, out);
        std::vector<float> rows(reference.pixels.size(), std::nanf(""));
        // Two bands, to cover the band split.
        const uint32_t half = out.height / 2;
        backend.renderRows(out, 0, half, rows.data());
        backend.renderRows(out, half, out.height, rows.data() + size_t(half) * out.width * c.image.channels);
        checkMatchesCore(rows, reference);
        if (c.scale == 1.0) CHECK(rows == c.image.pixels);  // vertices are reproduced exactly
    }
    CHECK(backend.validationMessages() == 0);
}

TEST_CASE("vulkan: no invocation is given more items than lavapipe's loop budget allows") {
    // lavapipe silently ends an invocation's loops after 65535 iterations in all; the
    // dispatch sizes must keep every invocation at kItemsPerInvocation items.
    for (uint64_t count : {0ull, 1ull, 63ull, 64ull, 1023ull, 1024ull, 1025ull, 3374026ull, 12578817ull, 67107840ull}) {
        INFO(count);
        const uint32_t groups = groupsFor(uint32_t(count));
        CHECK(groups <= kMaxGroups);
        CHECK(uint64_t(groups) * kGroupSize * kItemsPerInvocation >= count);
        CHECK((count == 0 || uint64_t(groups - 1) * kGroupSize * kItemsPerInvocation < count));
    }
}

TEST_CASE("vulkan: huge magnifications render in loop-bounded bands, equal to core", "[vulkan]") {
    // At ×150 one triangle covers hundreds of output columns, so a band holds only a few dozen
    // rows (the render loop budget); the result must still match core everywhere.
    const Image image = randomImage(9, 7, 3, 11);
    VulkanBackend backend = makeBackend("localmax");
    backend.prepare(image);
    backend.optimize();
    const OutputSize out = scaledOutputSize(image.width, image.height, 150.0);
    const Image reference = renderImage(backend.mesh(), image, out);
    std::vector<float> rows(reference.pixels.size(), std::nanf(""));
    backend.renderRows(out, 0, out.height, rows.data());
    checkMatchesCore(rows, reference);
    CHECK(backend.validationMessages() == 0);
}

TEST_CASE("vulkan: the validation messenger reports a deliberate error", "[vulkan]") {
    // Shows the zero-message checks above can fail: an invalid call must be counted.
    std::unique_ptr<VulkanContext> context = createContext({-1, true});
    REQUIRE(context->validation_messages == 0);
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, nullptr, 0, 16, 0, VK_SHARING_MODE_EXCLUSIVE, 0, nullptr};
    VkBuffer buffer = VK_NULL_HANDLE;  // usage 0 is invalid
    if (vkCreateBuffer(context->device, &info, nullptr, &buffer) == VK_SUCCESS) vkDestroyBuffer(context->device, buffer, nullptr);
    CHECK(context->validation_messages > 0);
}

TEST_CASE("vulkan: an input whose edge arrays exceed a 128 MiB binding runs and stays valid", "[vulkan]") {
    // 2100² has 13.2 M edges: 211 MB per edge array. A few flat regions keep flips, and the
    // test's time, small.
    const uint32_t side = 2100;
    Image image;
    image.width = side;
    image.height = side;
    image.channels = 1;
    image.pixels.resize(size_t(side) * side);
    for (uint32_t y = 0; y < side; ++y)
        for (uint32_t x = 0; x < side; ++x)
            image.pixels[size_t(y) * side + x] = (x + y < side ? 0.2f : 0.9f) + (x < side / 3 ? 0.05f : 0.0f);
    VulkanOptions options;
    options.rule = "localmax";
    VulkanBackend backend(options);
    backend.prepare(image);
    const OptimizeStats stats = backend.optimize();
    CHECK_FALSE(stats.capped);
    CHECK(stats.flips > 0);
    const Mesh mesh = backend.mesh();
    CHECK(checkMesh(mesh) == "");
    CHECK(stats.cost_final < stats.cost_init);

    // A band across the middle of a 2× output, against core's renderer on the same mesh.
    const OutputSize out = scaledOutputSize(side, side, 2.0);
    const uint32_t first = out.height / 2 - 8, rows = 16;
    std::vector<float> device_rows(size_t(rows) * out.width), core_rows(device_rows.size());
    backend.renderRows(out, first, first + rows, device_rows.data());
    MeshRenderer(mesh, image).renderRows(out, first, first + rows, core_rows.data());
    double worst = 0.0;
    for (size_t i = 0; i < core_rows.size(); ++i) worst = std::max(worst, double(std::abs(device_rows[i] - core_rows[i])));
    CHECK(worst <= 1.0 / 255.0);
    CHECK(backend.validationMessages() == 0);  // counted when scripts/test turns validation on
}

TEST_CASE("vulkan: the profile splits each kernel's device time by iteration, and the parts add up", "[vulkan]") {
    VulkanBackend backend = makeBackend("localmax", true, true);
    const Image image = fixture("crop32_astronaut.png");  // the backend reads it until prepared again
    backend.prepare(image);
    const OptimizeStats stats = backend.optimize();
    REQUIRE(stats.iterations > 1);
    const auto times = backend.kernelTimes();
    REQUIRE_FALSE(times.empty());
    for (const auto& [kernel, time] : times) {
        CAPTURE(kernel);
        // Every iteration the optimisation ran has its slot (batches may record more, left empty).
        CHECK(time.iteration_ms.size() >= stats.iterations);
        double sum = 0.0;
        for (double ms : time.iteration_ms) {
            CHECK(ms >= 0.0);
            sum += ms;
        }
        // The same terms added in another grouping: equal but for rounding.
        CHECK(sum == Approx(time.ms).epsilon(1e-9));
    }
    // The first iteration tests every edge: its candidates step takes time on any device.
    const auto candidates = std::find_if(times.begin(), times.end(), [](const auto& t) { return t.first == "candidates"; });
    REQUIRE(candidates != times.end());
    CHECK(candidates->second.iteration_ms[0] > 0.0);
    CHECK(backend.validationMessages() == 0);
}
