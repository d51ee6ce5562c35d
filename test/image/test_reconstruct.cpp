// The consistent reconstruction (core/image/reconstruct.h) on the CPU reference: consistency with
// the documented footprint model on smooth inputs, bounded overshoot at steps, flat stays flat,
// the identity at s = 1 and continuity near it, colour ≤ alpha, determinism, and tiles.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "backend.h"
#include "lawson.h"
#include "parallel.h"
#include "reconstruct.h"
#include "render.h"
#include "test_support.h"
#include "tiled_upscale.h"

namespace {

using namespace ddt;

Mesh optimisedMesh(const Image& image) {
    std::unique_ptr<Backend> backend = makeCpuBackend();
    backend->prepare(image);
    backend->optimize();
    return backend->mesh();
}

// The model as core/image/reconstruct.h documents it, written here independently: per axis a
// Gaussian of σ = 0.4·√(1 − 1/s²) input pixels on offsets t/3, |t| ≤ ceil(9σ), normalised;
// the surface sampled at the 3× supersampling (render.h's sampling at out = 3w × 3h), samples
// past the border taken from the nearest one.
std::vector<double> modelTaps(double scale) {
    const double sigma = 0.4 * std::sqrt(1.0 - 1.0 / (scale * scale));
    const int radius = int(std::ceil(9.0 * sigma));
    std::vector<double> taps;
    double total = 0.0;
    for (int t = -radius; t <= radius; ++t) taps.push_back(std::exp(-(t / 3.0) * (t / 3.0) / (2 * sigma * sigma)));
    for (double tap : taps) total += tap;
    for (double& tap : taps) tap /= total;
    return taps;
}

// A named resize filter's taps as core/image/reconstruct.h documents them (at any factor above 1),
// written here from the filters' textbook formulas: weight(t/3) for |t/3| < support (the
// support's own taps weigh 0), normalised.
std::vector<double> filterTaps(AssumedKernel kernel) {
    const double pi = 3.14159265358979323846;
    auto sinc = [&](double x) { return x == 0.0 ? 1.0 : std::sin(pi * x) / (pi * x); };
    auto weight = [&](double x) {
        const double a = std::abs(x);
        switch (kernel) {
        case AssumedKernel::box: return a < 0.5 ? 1.0 : 0.0;  // no tap at ±0.5 on the thirds
        case AssumedKernel::bicubic:  // Keys, a = −0.5
            return a < 1 ? 1.5 * a * a * a - 2.5 * a * a + 1 : a < 2 ? -0.5 * a * a * a + 2.5 * a * a - 4 * a + 2 : 0.0;
        case AssumedKernel::lanczos3: return a < 3 ? sinc(x) * sinc(x / 3) : 0.0;
        case AssumedKernel::footprint:
        case AssumedKernel::mixed: break;
        }
        return 0.0;
    };
    const double support = kernel == AssumedKernel::box ? 0.5 : kernel == AssumedKernel::bicubic ? 2.0 : 3.0;
    std::vector<double> taps;
    for (int t = -9; t <= 9; ++t)
        if (std::abs(t / 3.0) < support) taps.push_back(weight(t / 3.0));
    double total = 0.0;
    for (double tap : taps) total += tap;
    for (double& tap : taps) tap /= total;
    return taps;
}

// D(surface) at every input pixel, for a grey image, with these taps per axis.
std::vector<double> degraded(const Mesh& mesh, const Surface& surface, const std::vector<double>& taps) {
    const uint32_t w = mesh.width, h = mesh.height;
    const Image sub = renderImage(mesh, surface.values, {3 * w, 3 * h}, surface.bubbles.data());
    const int r = int(taps.size() / 2);
    std::vector<double> result(size_t(w) * h, 0.0);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            for (int ty = -r; ty <= r; ++ty)
                for (int tx = -r; tx <= r; ++tx) {
                    const int sx = std::clamp(int(3 * x + 1) + tx, 0, int(3 * w - 1));
                    const int sy = std::clamp(int(3 * y + 1) + ty, 0, int(3 * h - 1));
                    result[size_t(y) * w + x] += taps[tx + r] * taps[ty + r] * sub.pixels[size_t(sy) * 3 * w + sx];
                }
    return result;
}

std::vector<double> degraded(const Mesh& mesh, const Surface& surface, double scale) {
    return degraded(mesh, surface, modelTaps(scale));
}

struct Residual {
    double rms = 0.0, largest = 0.0;
};

// Over the pixels two or more from the frame (a grey image): the ramp below has its extremes
// on the frame, where the overshoot bound binds.
Residual interiorResidualOf(const Image& input, const std::vector<double>& degraded_values) {
    Residual r;
    size_t count = 0;
    for (uint32_t y = 2; y + 2 < input.height; ++y)
        for (uint32_t x = 2; x + 2 < input.width; ++x) {
            const size_t i = size_t(y) * input.width + x;
            const double d = std::abs(input.pixels[i] - degraded_values[i]);
            r.rms += d * d;
            r.largest = std::max(r.largest, d);
            ++count;
        }
    r.rms = std::sqrt(r.rms / count);
    return r;
}

// A smooth grey image without local extrema (where the overshoot bound never binds): rising
// in x and y with curvature in both, values in [0.1, 0.9].
Image smoothImage(uint32_t w, uint32_t h) {
    std::vector<float> pixels;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const double u = double(x) / (w - 1), v = double(y) / (h - 1);
            pixels.push_back(float(0.1 + 0.45 * u * u + 0.25 * std::sqrt(v) + 0.1 * u * v));
        }
    return test::makeImage(w, h, 1, pixels);
}

// Two waves over 40 × 30 grey pixels, 0.5 ± 0.3, their frequencies `k` times the slow ones'.
Image wavyImage(double k) {
    std::vector<float> pixels;
    for (uint32_t y = 0; y < 30; ++y)
        for (uint32_t x = 0; x < 40; ++x)
            pixels.push_back(float(0.5 + 0.15 * std::sin(k * (0.45 * x + 0.2 * y)) + 0.15 * std::cos(k * (0.3 * y - 0.1 * x))));
    return test::makeImage(40, 30, 1, pixels);
}

}  // namespace

TEST_CASE("reconstruct: on a smooth input the output, degraded by the model, gives the input back") {
    const Image input = smoothImage(40, 30);
    const Mesh mesh = optimisedMesh(input);
    for (double scale : {2.0, 4.0, 8.0}) {
        const Residual consistent = interiorResidualOf(
            input, degraded(mesh, reconstructSurface(mesh, input, degradationFor(scale, scale, AssumedKernel::footprint)), scale));
        CAPTURE(scale, consistent.rms, consistent.largest);
        // The stated tolerance: half a level of 8 bits (the input's quantisation tolerance:
        // residuals within it are not chased) plus a quarter level that three SART steps may
        // leave. Measured: at most 0.0020 against 0.0029 allowed.
        CHECK(consistent.largest <= (0.5 + 0.25) / 255);
    }
}

TEST_CASE("reconstruct: a named resize filter's taps are the filter's weights on the thirds, at every factor above 1") {
    for (AssumedKernel kernel : {AssumedKernel::box, AssumedKernel::bicubic, AssumedKernel::lanczos3}) {
        const std::vector<double> expected = filterTaps(kernel);
        for (double scale : {1.25, 2.0, 8.0}) {
            const std::vector<float> taps = degradationTaps(kernel, degradationFor(scale, scale, kernel).width_x);
            CAPTURE(assumedKernelName(kernel), scale);
            REQUIRE(taps.size() == expected.size());
            for (size_t i = 0; i < taps.size(); ++i) CHECK(taps[i] == Approx(expected[i]).margin(1e-7));  // float rounding
        }
        CHECK(degradationFor(1.0, 1.0, kernel).identity());
    }
    // The footprint's stay the Gaussian of σ = 0.4·√(1 − 1/s²).
    const std::vector<float> footprint =
        degradationTaps(AssumedKernel::footprint, degradationFor(2.0, 2.0, AssumedKernel::footprint).width_x);
    const std::vector<double> expected = modelTaps(2.0);
    REQUIRE(footprint.size() == expected.size());
    for (size_t i = 0; i < footprint.size(); ++i) CHECK(footprint[i] == Approx(expected[i]).margin(1e-7));
}

// `taps` centred in `size` taps, zeros on either side.
std::vector<double> padded(const std::vector<double>& taps, size_t size) {
    std::vector<double> result(size, 0.0);
    for (size_t i = 0; i < taps.size(); ++i) result[(size - taps.size()) / 2 + i] = taps[i];
    return result;
}

TEST_CASE("reconstruct: mixed's taps are half the footprint's and half bicubic's at full width, centred") {
    for (double scale : {1.25, 2.0, 8.0}) {
        const std::vector<double> footprint = modelTaps(scale), bicubic = filterTaps(AssumedKernel::bicubic);
        const size_t size = std::max(footprint.size(), bicubic.size());
        const std::vector<double> a = padded(footprint, size), b = padded(bicubic, size);
        const std::vector<float> taps = degradationTaps(AssumedKernel::mixed, degradationFor(scale, scale).width_x);
        CAPTURE(scale);
        REQUIRE(taps.size() == size);
        for (size_t i = 0; i < size; ++i) CHECK(taps[i] == Approx(0.5 * a[i] + 0.5 * b[i]).margin(1e-7));  // float rounding
    }
}

TEST_CASE("reconstruct: the mixed surface lies between the two it mixes") {
    // Degraded by the footprint it is closer to the input than bicubic's surface; by bicubic,
    // closer than the footprint's.
    const Image input = wavyImage(2.0);
    const Mesh mesh = optimisedMesh(input);
    auto surface = [&](AssumedKernel kernel) { return reconstructSurface(mesh, input, degradationFor(4.0, 4.0, kernel)); };
    const Surface mixed = surface(AssumedKernel::mixed), footprint = surface(AssumedKernel::footprint),
                  bicubic = surface(AssumedKernel::bicubic);
    const std::vector<double> footprint_taps = modelTaps(4.0), bicubic_taps = filterTaps(AssumedKernel::bicubic);
    auto rms = [&](const Surface& s, const std::vector<double>& taps) {
        return interiorResidualOf(input, degraded(mesh, s, taps)).rms;
    };
    CHECK(rms(mixed, footprint_taps) < rms(bicubic, footprint_taps));
    CHECK(rms(mixed, bicubic_taps) < rms(footprint, bicubic_taps));
}

TEST_CASE("reconstruct: the surface assuming a filter is more consistent with that filter than the footprint's") {
    const Image input = wavyImage(2.0);  // faster waves, where the filters differ more
    const Mesh mesh = optimisedMesh(input);
    const Surface footprint = reconstructSurface(mesh, input, degradationFor(4.0, 4.0, AssumedKernel::footprint));
    for (AssumedKernel kernel : {AssumedKernel::box, AssumedKernel::bicubic, AssumedKernel::lanczos3}) {
        const std::vector<double> taps = filterTaps(kernel);
        const Residual right =
            interiorResidualOf(input, degraded(mesh, reconstructSurface(mesh, input, degradationFor(4.0, 4.0, kernel)), taps));
        const Residual wrong = interiorResidualOf(input, degraded(mesh, footprint, taps));
        CAPTURE(assumedKernelName(kernel), right.rms, wrong.rms);
        CHECK(right.rms < wrong.rms);
    }
}

TEST_CASE("reconstruct: on a wavy input the residual drops well below plain DDT's") {
    // Two slow waves: their crests are local extrema, where the bound keeps the surface from
    // rising above the input (bounded overshoot wins), so only part of the residual can go.
    const Image input = wavyImage(1.0);
    const Mesh mesh = optimisedMesh(input);
    const Surface plain{input, UninitialisedVector<float>(size_t(mesh.edgeCount()), 0.0f)};  // linear: the paper's surface
    for (double scale : {2.0, 4.0, 8.0}) {
        const Residual before = interiorResidualOf(input, degraded(mesh, plain, scale));
        const Residual after = interiorResidualOf(
            input, degraded(mesh, reconstructSurface(mesh, input, degradationFor(scale, scale, AssumedKernel::footprint)), scale));
        CAPTURE(scale, before.rms, after.rms);
        CHECK(after.rms < before.rms / 2);  // measured: 2.9× to 3.4× lower
    }
}

TEST_CASE("reconstruct: a flat image stays exactly flat") {
    for (uint32_t channels : {1u, 3u, 4u}) {
        const Image input = test::makeImage(17, 11, channels, std::vector<float>(17 * 11 * channels, 0.375f));
        const Mesh mesh = optimisedMesh(input);
        const Surface surface = reconstructSurface(mesh, input, degradationFor(3.3, 3.3));
        const Image out = renderImage(mesh, surface.values, scaledOutputSize(17, 11, 3.3), surface.bubbles.data());
        CAPTURE(channels);
        CHECK(std::all_of(out.pixels.begin(), out.pixels.end(), [](float v) { return v == 0.375f; }));
    }
}

TEST_CASE("reconstruct: a step edge keeps its plateaus and never overshoots them") {
    // A vertical step 0.2 | 0.8 between columns 9 and 10 of a 20×12 grey image.
    std::vector<float> pixels;
    for (uint32_t y = 0; y < 12; ++y)
        for (uint32_t x = 0; x < 20; ++x) pixels.push_back(x < 10 ? 0.2f : 0.8f);
    const Image input = test::makeImage(20, 12, 1, pixels);
    const Mesh mesh = optimisedMesh(input);
    const double scale = 4.0;
    const Surface surface = reconstructSurface(mesh, input, degradationFor(scale, scale));
    const Image out = renderImage(mesh, surface.values, scaledOutputSize(20, 12, scale), surface.bubbles.data());
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x) {
            const float v = out.pixels[size_t(y) * out.width + x];
            const double u = (x + 0.5) / scale - 0.5;  // the sample's input column
            CAPTURE(x, y, u, v);
            // The bound: the 3 × 3 input range around each vertex, no margin.
            CHECK(v >= 0.2f);
            CHECK(v <= 0.8f);
            // Samples whose triangles lie two or more pixels from the step see a flat 3 × 3.
            if (u <= 7.0) CHECK(v == 0.2f);
            if (u >= 12.0) CHECK(v == 0.8f);
        }
}

TEST_CASE("reconstruct: s = 1 is the identity, and the footprint's surface moves continuously away from it") {
    const Image input = test::photoCrop();
    const Mesh mesh = optimisedMesh(input);
    for (AssumedKernel kernel : {AssumedKernel::mixed, AssumedKernel::footprint, AssumedKernel::bicubic}) {
        CAPTURE(assumedKernelName(kernel));
        CHECK(degradationFor(1.0, 1.0, kernel).identity());
        const Surface at_one = reconstructSurface(mesh, input, degradationFor(1.0, 1.0, kernel));
        CHECK(test::samePixels(at_one.values.pixels, input.pixels));
        const Image out = renderImage(mesh, at_one.values, {input.width, input.height}, at_one.bubbles.data());
        CHECK(test::samePixels(out.pixels, input.pixels));
    }

    // The footprint's width grows from 0; a resize filter's (and mixed's bicubic part) is
    // whole at every s > 1, as a resize by any factor stretches it to the small image's pixels.
    auto distance = [&](double scale) {
        const Surface s = reconstructSurface(mesh, input, degradationFor(scale, scale, AssumedKernel::footprint));
        float largest = 0.0f;
        for (size_t i = 0; i < input.pixels.size(); ++i)
            largest = std::max(largest, std::abs(s.values.pixels[i] - input.pixels[i]));
        return largest;
    };
    const float d_101 = distance(1.01), d_11 = distance(1.1), d_2 = distance(2.0);
    CAPTURE(d_101, d_11, d_2);
    CHECK(d_101 <= d_11);
    CHECK(d_11 < d_2);
    CHECK(d_101 < 0.01f);  // σ(1.01) = 0.056 pixels: the footprint is nearly a point
}

TEST_CASE("reconstruct: premultiplied colour never exceeds alpha, and values stay in [0, 1]") {
    std::mt19937 rng(3);
    Image input = test::randomImage(rng, 40, 30, 4);
    for (size_t p = 0; p < size_t(40) * 30; ++p)  // premultiply, as the reader does
        for (uint32_t k = 0; k < 3; ++k) input.pixels[p * 4 + k] *= input.pixels[p * 4 + 3];
    const Mesh mesh = optimisedMesh(input);
    const Surface surface = reconstructSurface(mesh, input, degradationFor(2.5, 2.5));
    const Image out = renderImage(mesh, surface.values, scaledOutputSize(40, 30, 2.5), surface.bubbles.data());
    bool ok = true;
    for (size_t p = 0; p < size_t(out.width) * out.height; ++p) {
        const float* v = &out.pixels[p * 4];
        for (uint32_t k = 0; k < 4; ++k) ok = ok && v[k] >= 0.0f && v[k] <= 1.0f;
        for (uint32_t k = 0; k < 3; ++k) ok = ok && v[k] <= v[3];
    }
    CHECK(ok);
}

TEST_CASE("reconstruct: the same surface on every run (no order-dependent sums)") {
    const Image input = test::photoCrop();
    const Mesh mesh = optimisedMesh(input);
    const Surface a = reconstructSurface(mesh, input, degradationFor(3.0, 2.0));
    const Surface b = reconstructSurface(mesh, input, degradationFor(3.0, 2.0));
    CHECK(test::samePixels(a.values.pixels, b.values.pixels));
    CHECK(test::samePixels(a.bubbles, b.bubbles));
}

// The triangles are split into runs by the thread count (core/image/reconstruct.cpp), and the
// vertices and edges on the runs' borders are summed apart from the rest: another split must
// still give every sum in the same order. 300×200 pixels is 119 000 triangles: 4 runs on one
// thread, 12 on three.
TEST_CASE("reconstruct: the same surface whatever the thread count splits the work into") {
    const Image input = test::photoCrop();
    const Mesh mesh = optimisedMesh(input);
    const unsigned threads = threadCount();
    setThreadCount(1);
    const Surface one = reconstructSurface(mesh, input, degradationFor(3.0, 2.0));
    setThreadCount(3);
    const Surface three = reconstructSurface(mesh, input, degradationFor(3.0, 2.0));
    setThreadCount(threads);
    CHECK(test::samePixels(one.values.pixels, three.values.pixels));
    CHECK(test::samePixels(one.bubbles, three.bubbles));
}

// takeMesh hands the CPU backend's mesh over instead of copying it (the sample and simplified
// paths render it themselves): the same records as mesh(), then nothing until prepared again.
TEST_CASE("backend: takeMesh gives the CPU backend's optimised mesh up, and it must be prepared again") {
    const Image input = test::photoCrop();
    std::unique_ptr<Backend> backend = makeCpuBackend();
    backend->prepare(input);
    backend->optimize();
    const Mesh copy = backend->mesh();
    const Mesh taken = backend->takeMesh();
    REQUIRE(taken.edgeCount() == copy.edgeCount());
    for (uint32_t e = 0; e < copy.edgeCount(); ++e) {
        const EdgeVertices& v = taken.vertices[e];
        const EdgeNeighbours& n = taken.neighbours[e];
        REQUIRE((v.a == copy.vertices[e].a && v.b == copy.vertices[e].b && v.l == copy.vertices[e].l &&
                 v.r == copy.vertices[e].r));
        REQUIRE((n.bl == copy.neighbours[e].bl && n.la == copy.neighbours[e].la && n.ar == copy.neighbours[e].ar &&
                 n.rb == copy.neighbours[e].rb));
    }
    CHECK_THROWS_AS(backend->mesh(), std::logic_error);
    CHECK_THROWS_AS(backend->optimize(), std::logic_error);
    backend->prepare(input);
    CHECK(backend->mesh().edgeCount() == taken.edgeCount());
}

// The CPU backend gives up its mesh in reconstruct (core/backend/backend.h): what needs the mesh
// afterwards is refused rather than run on an empty one.
TEST_CASE("reconstruct: the CPU backend refuses optimize and mesh after reconstruct, until prepared again") {
    const Image input = test::photoCrop();
    std::unique_ptr<Backend> backend = makeCpuBackend();
    backend->prepare(input);
    backend->optimize();
    backend->reconstruct(degradationFor(2.0, 2.0));
    CHECK_THROWS_AS(backend->optimize(), std::logic_error);
    CHECK_THROWS_AS(backend->mesh(), std::logic_error);
    std::vector<float> rows(size_t(input.width) * 2 * input.channels);
    backend->renderRows({input.width * 2, input.height * 2}, 0, 1, rows.data());  // its surface still renders
    backend->prepare(input);
    CHECK(backend->mesh().edgeCount() == gridEdgeCount(input.width, input.height));
}

TEST_CASE("reconstruct: tiled and untiled consistent upscales agree (CPU)") {
    const Image input = test::photoCrop();
    const OutputSize out = scaledOutputSize(input.width, input.height, 2.5);
    std::unique_ptr<Backend> backend = makeCpuBackend();
    // The footprint, and lanczos3: the widest taps, which reach furthest.
    for (AssumedKernel kernel : {AssumedKernel::footprint, AssumedKernel::lanczos3}) {
        auto upscale = [&](uint32_t tile) {
            std::vector<float> result(size_t(out.width) * out.height * input.channels);
            TileOptions options;
            options.tile = tile;
            options.reconstruct = true;
            options.kernel = kernel;
            PackedImage packed(input);
            upscaleRows(*backend, packed, out, options, [&](OutputRows&& rows) {
                std::copy_n(rows.floats.get(), size_t(rows.rows()) * out.width * input.channels,
                            result.begin() + size_t(rows.y_begin) * out.width * input.channels);
            });
            return result;
        };
        const test::Agreement a = test::compareSamples(upscale(64), upscale(0));
        std::printf("reconstruct: %s, tiled (64, overlap %u) vs untiled, x2.5: max difference %.5f (%.2f/255), %.4f %% "
                    "within 1/255\n",
                    assumedKernelName(kernel), kDefaultOverlap, a.max_difference, a.max_difference * 255.0f,
                    100.0 * a.within_one_level);
        CAPTURE(assumedKernelName(kernel));
        // Each crop is reconstructed on its own, but the corrections' reach (about a pixel per
        // step with the footprint, a few with lanczos3's six-pixel taps) ends inside the
        // 16-pixel overlap: what is left is float summation order in the sums around each
        // vertex, whose triangles are listed from other edge ids. Measured: at most 4e-5 (the
        // footprint) and 7e-5 (lanczos3); 1e-4 is a fortieth of an 8-bit level, while a seam
        // moves samples by 1e-2.
        CHECK(a.max_difference <= 1e-4f);
    }
}

TEST_CASE("reconstruct: the default assumption is the footprint for a JPEG file and mixed for anything else") {
    CHECK(automaticAssumption("jpeg") == AssumedKernel::footprint);
    CHECK(automaticAssumption("png") == AssumedKernel::mixed);
    CHECK(automaticAssumption("openexr") == AssumedKernel::mixed);
    CHECK(automaticAssumption("") == AssumedKernel::mixed);  // an image made in memory
}
