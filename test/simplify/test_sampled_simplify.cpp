// Simplifying a triangulation of samples (--mask's known pixels, a point file's points): the
// collapses keep the samples' convex hull (core/simplify/edge_collapse.h), so every sample is
// still rendered by the mesh; the mesh stays valid; the target is reached; and the kept
// vertices' colours are fitted to the samples alone (core/simplify/colour_fit.h). On a device,
// the parallel rule's kernels give core's parallel rule's mesh and colours, bit for bit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "colour_fit.h"
#include "context.h"
#include "delaunay.h"
#include "greedy_simplify.h"
#include "parallel_simplify.h"
#include "sampled_render.h"
#include "simplify/device_simplify.h"
#include "test_support.h"

using namespace ddt;

namespace {

// A mesh of samples and their values (by vertex id), optimised by the CPU backend as a
// --mask or point-file run optimises it.
struct Samples {
    Mesh mesh;
    Image values;
};

Mesh optimised(const Image& values, Mesh mesh) {
    std::unique_ptr<Backend> backend = makeCpuBackend();
    backend->prepareFrom(values, std::move(mesh));
    backend->optimize();
    return backend->takeMesh();
}

// photoPiece()'s pixels where a random 60 % are known, the top-left and bottom-right corners
// cut off (x + y < 12, and the same from the other corner), so the hull is not the rectangle.
Samples maskSamples(const Image& picture) {
    std::mt19937 rng(11);
    std::bernoulli_distribution known(0.6);
    std::vector<uint32_t> ids;
    const uint32_t w = picture.width, h = picture.height;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            if (x + y >= 12 && (w - 1 - x) + (h - 1 - y) >= 12 && known(rng)) ids.push_back(y * w + x);
    return {optimised(picture, delaunayOfPixels(w, h, ids)), picture};
}

// 1500 points at random multiples of 1/1024 pixel in a 100 × 70 frame, with the colour of
// photoPiece()'s nearest pixel: a point file's general form (explicit positions, n × 1 values).
Samples pointSamples(const Image& picture) {
    std::mt19937 rng(12);
    std::uniform_int_distribution<int32_t> fx(0, int32_t(picture.width - 1) * kPositionOne),
        fy(0, int32_t(picture.height - 1) * kPositionOne);
    std::vector<Position> places;
    for (int i = 0; i < 1500; ++i) places.push_back({fx(rng), fy(rng)});
    std::sort(places.begin(), places.end(), [](Position p, Position q) { return p.y != q.y ? p.y < q.y : p.x < q.x; });
    places.erase(std::unique(places.begin(), places.end()), places.end());
    std::vector<float> pixels;
    for (const Position& p : places) {
        const uint32_t x = uint32_t((p.x + kPositionOne / 2) / kPositionOne), y = uint32_t((p.y + kPositionOne / 2) / kPositionOne);
        const float* pixel = picture.pixels.data() + (size_t(y) * picture.width + x) * picture.channels;
        pixels.insert(pixels.end(), pixel, pixel + picture.channels);
    }
    Image values = test::makeImage(uint32_t(places.size()), 1, picture.channels, pixels);
    return {optimised(values, delaunayOfPoints(picture.width, picture.height, places)), values};
}

// Twice the area the triangles cover, exactly: with the samples inside the hull, an equal area
// means the same hull.
int64_t twiceCoveredArea(const Mesh& mesh) {
    int64_t area = 0;
    forEachTriangle(mesh, [&](const Triangle& t) {
        const Position p = positionOf(mesh, t.v0), q = positionOf(mesh, t.v1), r = positionOf(mesh, t.v2);
        area += positionOrient(p.x, p.y, q.x, q.y, r.x, r.y);
    });
    return area;
}

// How many of `samples` lie outside the mesh's hull (on it counts as inside).
size_t samplesOutside(const Mesh& mesh, const std::vector<KnownSample>& samples) {
    size_t outside = 0;
    for (const KnownSample& sample : samples) {
        bool inside = true;
        for (const EdgeVertices& v : mesh.vertices) {
            if (v.l != kNone && v.r != kNone) continue;
            // The hull's inside is the side of its one triangle.
            const Position a = positionOf(mesh, v.l != kNone ? v.a : v.b), b = positionOf(mesh, v.l != kNone ? v.b : v.a);
            inside = inside && positionOrient(a.x, a.y, b.x, b.y, sample.place.x, sample.place.y) >= 0;
        }
        outside += !inside;
    }
    return outside;
}

using Simplifier = std::function<SimplifyStats(Mesh&, Image&, uint32_t, double)>;
const std::pair<const char*, Simplifier> kSimplifiers[] = {
    {"serial", [](Mesh& m, Image& v, uint32_t t, double e) { return simplifySerial(m, v, t, e); }},
    {"parallel", [](Mesh& m, Image& v, uint32_t t, double e) { return SimplifyStats(simplifyParallel(m, v, t, e)); }},
};

}  // namespace

TEST_CASE("sampled simplify: a mask's and a point file's meshes keep their hull, every sample in it, at the target") {
    const Image picture = test::photoPiece();
    for (const bool points : {false, true}) {
        const Samples start = points ? pointSamples(picture) : maskSamples(picture);
        REQUIRE(checkMesh(start.mesh, MeshHull::convex) == "");
        REQUIRE(checkMesh(start.mesh, MeshHull::rectangle) != "");  // the cut corners: not the grid's rules
        const std::vector<KnownSample> samples = knownSamplesOf(start.mesh);
        const uint32_t target = uint32_t(samples.size() / 10);
        for (const auto& [name, simplify] : kSimplifiers) {
            INFO((points ? "points, " : "mask, ") << name);
            Mesh mesh = start.mesh;
            Image values = start.values;
            const SimplifyStats stats = simplify(mesh, values, target, 0.0);
            CHECK(stats.vertices_after == target);
            CHECK(usedVertexCount(mesh) == target);
            CHECK(mesh.hull == MeshHull::convex);
            CHECK(checkMesh(mesh, MeshHull::convex) == "");
            CHECK(samplesOutside(mesh, samples) == 0);
            CHECK(twiceCoveredArea(mesh) == twiceCoveredArea(start.mesh));
        }
    }
}

TEST_CASE("sampled simplify: with a largest error, no collapse exceeds it and fewer vertices go") {
    const Image picture = test::photoPiece();
    const Samples start = maskSamples(picture);
    const std::vector<KnownSample> samples = knownSamplesOf(start.mesh);
    uint32_t kept[2];
    int i = 0;
    for (const double max_error : {2.0, 8.0}) {
        Mesh mesh = start.mesh;
        Image values = start.values;
        const SimplifyStats stats = simplifySerial(mesh, values, 3, max_error);
        INFO("max error " << max_error);
        CHECK(stats.vertices_after > 3);  // the error, not the target, ended it
        CHECK(checkMesh(mesh, MeshHull::convex) == "");
        CHECK(samplesOutside(mesh, samples) == 0);
        kept[i++] = stats.vertices_after;
    }
    CHECK(kept[0] > kept[1]);               // a larger error allows more collapses
    CHECK(kept[0] < uint32_t(samples.size()));  // and even 2 levels allow some
}

TEST_CASE("sampled simplify: a plane comes back exactly from a tenth of a mask's pixels") {
    // f = 0.1 + 0.006 x + 0.008 y on 100 × 70: values in [0.1, 0.75], so no clamping.
    const uint32_t w = 100, h = 70;
    auto plane = [](double x, double y) { return 0.1 + 0.006 * x + 0.008 * y; };
    std::vector<float> pixels;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) pixels.push_back(float(plane(x, y)));
    Image picture = test::makeImage(w, h, 1, pixels);
    picture.sample_type = SampleType::Float;
    // Every corner known (the hull is the rectangle, so the render at ×1 is the mesh's
    // everywhere), a random half of the rest.
    std::mt19937 rng(13);
    std::bernoulli_distribution known(0.5);
    std::vector<uint32_t> ids;
    for (uint32_t v = 0; v < w * h; ++v)
        if (v == 0 || v == w - 1 || v == w * (h - 1) || v == w * h - 1 || known(rng)) ids.push_back(v);
    const Mesh start = optimised(picture, delaunayOfPixels(w, h, ids));
    for (const auto& [name, simplify] : kSimplifiers) {
        INFO(name);
        Mesh mesh = start;
        Image values = picture;
        simplify(mesh, values, uint32_t(ids.size() / 10), 0.0);
        REQUIRE(usedVertexCount(mesh) == ids.size() / 10);
        const Image out = renderSampledMesh(mesh, values, {w, h});
        double worst = 0.0;
        for (uint32_t v : ids) worst = std::max(worst, std::abs(out.pixels[v] - plane(v % w, v / w)));
        // Every triangle's plane is f's, so every collapse costs nothing and every kept vertex's
        // colour is f where it stands; what is left is float: the values' 7 digits, the fit's
        // stop at 1e-6 of its right-hand side, float barycentric weights.
        CHECK(worst < 1e-5);
    }
}

TEST_CASE("sampled simplify: the unknown pixels' values are never read") {
    const Image picture = test::photoPiece();
    const Samples start = maskSamples(picture);
    const std::vector<bool> used = usedVertices(start.mesh);
    // The same known pixels, the unknown ones all `value`.
    auto filled = [&](float value) {
        Image image = picture;
        for (uint32_t v = 0; v < picture.width * picture.height; ++v)
            for (uint32_t k = 0; k < picture.channels; ++k)
                if (!used[v]) image.pixels[size_t(v) * picture.channels + k] = value;
        return image;
    };
    const uint32_t target = usedVertexCount(start.mesh) / 10;
    for (const auto& [name, simplify] : kSimplifiers) {
        INFO(name);
        Mesh dark_mesh = start.mesh, light_mesh = start.mesh;
        Image dark = filled(0.0f), light = filled(1.0f);
        simplify(dark_mesh, dark, target, 0.0);
        simplify(light_mesh, light, target, 0.0);
        CHECK(test::sameRecords(dark_mesh, light_mesh));
        const std::vector<bool> kept = usedVertices(dark_mesh);
        size_t differing = 0;
        for (uint32_t v = 0; v < picture.width * picture.height; ++v)
            for (uint32_t k = 0; k < picture.channels; ++k)
                differing += kept[v] && dark.pixels[size_t(v) * picture.channels + k] !=
                                            light.pixels[size_t(v) * picture.channels + k];
        CHECK(differing == 0);
    }
}

TEST_CASE("sampled simplify: on the device a mask's and a point file's meshes simplify as by simplifyParallel",
          "[vulkan]") {
    std::unique_ptr<VulkanContext> context = createContext({-1, true});
    const Image picture = test::photoPiece();
    for (const bool points : {false, true}) {
        const Samples start = points ? pointSamples(picture) : maskSamples(picture);
        // To a tenth, and as far as 6 levels allow.
        for (const double max_error : {0.0, 6.0}) {
            INFO((points ? "points" : "mask") << ", max error " << max_error);
            const uint32_t target = usedVertexCount(start.mesh) / 10;
            Mesh core_mesh = start.mesh, device_mesh = start.mesh;
            Image core_values = start.values, device_values = start.values;
            const ParallelSimplifyStats core = simplifyParallel(core_mesh, core_values, target, max_error);
            const ParallelSimplifyStats device = simplifyOnDevice(*context, device_mesh, device_values, target, max_error);
            if (max_error == 0.0) CHECK(device.vertices_after == target);
            CHECK(device.vertices_after == core.vertices_after);
            CHECK(device.rounds == core.rounds);
            CHECK(test::sameRecords(device_mesh, core_mesh));
            CHECK(test::samePixels(device_values.pixels, core_values.pixels));
            CHECK(checkMesh(device_mesh, MeshHull::convex) == "");
        }
    }
    CHECK(context->validation_messages == 0);
}
