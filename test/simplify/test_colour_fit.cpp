// The least-squares colours of a simplified mesh (core/simplify/colour_fit.h): a picture the
// mesh can hold exactly is found again, a fit never errs more at the pixel centres than its
// start, and the sample type's range and alpha are kept.
#include <catch2/catch.hpp>

#include <random>

#include "colour_fit.h"
#include "greedy_simplify.h"
#include "vertex_quadrics.h"
#include "render.h"
#include "test_support.h"

using namespace ddt;
using namespace ddt::test;

namespace {

// The squared error of the mesh's surface with `colours` at the pixel centres of `picture`
// (a render at ×1 samples exactly there).
double pixelError(const Mesh& mesh, const Image& colours, const Image& picture) {
    const Image surface = renderImage(mesh, colours, {picture.width, picture.height});
    double sum = 0.0;
    for (size_t i = 0; i < picture.pixels.size(); ++i) sum += (surface.pixels[i] - picture.pixels[i]) * double(surface.pixels[i] - picture.pixels[i]);
    return sum;
}

}  // namespace

TEST_CASE("colour fit: a plane is found again on a simplified mesh") {
    // Vertex colours on the plane z = 0.3 + x/64 − y/128 make the surface match every pixel of
    // that plane: the least-squares solution, found from a start off the plane by up to 0.2
    // (μ = 1e-3 pulls towards the start, against several pixels per vertex, and the conjugate
    // gradients stop at 1e-6 of the right-hand side: within 1e-3 of the plane).
    std::mt19937 rng(5);
    const uint32_t w = 40, h = 30;
    Mesh mesh = optimisedGridMesh(randomImage(rng, w, h, 1));
    Image shape = randomImage(rng, w, h, 1);
    simplifySerial(mesh, shape, w * h / 5);  // moved vertices, a few pixels each
    REQUIRE(checkMesh(mesh) == "");
    auto plane = [](double x, double y) { return 0.3 + x / 64 - y / 128; };
    std::vector<float> pixels;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) pixels.push_back(float(plane(x, y)));
    const Image picture = makeImage(w, h, 1, pixels);
    Image colours = picture;
    std::uniform_real_distribution<float> off(-0.2f, 0.2f);
    for (float& value : colours.pixels) value += off(rng);
    fitColours(mesh, picture, colours);
    double worst = 0.0;
    const std::vector<bool> used = usedVertices(mesh);
    for (uint32_t v = 0; v < w * h; ++v) {
        if (!used[v]) continue;
        const Position p = mesh.positions[v];
        worst = std::max(worst, std::abs(colours.pixels[v] - plane(p.x / 1024.0, p.y / 1024.0)));
    }
    CHECK(worst < 1e-3);
}

TEST_CASE("colour fit: the fitted colours err less at the pixel centres than the quadrics' own") {
    std::mt19937 rng(9);
    for (uint32_t channels : {1u, 3u}) {
        Image picture = randomImage(rng, 24, 18, channels);
        picture.sample_type = SampleType::Float;  // no clamp: the fit's own minimum
        Mesh mesh = optimisedGridMesh(picture);
        Image colours = picture;
        simplifySerial(mesh, colours, 24 * 18 / 5);  // its colours fitted already
        REQUIRE(checkMesh(mesh) == "");
        Image start = colours;
        for (float& value : start.pixels) value = std::clamp(value + 0.05f, 0.0f, 1.0f);
        Image fitted = start;
        fitColours(mesh, picture, fitted);
        INFO(channels << " channels");
        CHECK(pixelError(mesh, fitted, picture) < pixelError(mesh, start, picture));
        // From a start that is already the fit, it barely moves (the residual's stop).
        Image again = colours;
        fitColours(mesh, picture, again);
        CHECK(pixelError(mesh, again, picture) == Approx(pixelError(mesh, colours, picture)).epsilon(1e-6));
    }
}

TEST_CASE("colour fit: 8-bit colours stay in [0, 1], premultiplied ones within their alpha") {
    // A checkerboard of 0 and 1 with alpha: an unclamped fit overshoots at its edges.
    std::vector<float> pixels;
    const uint32_t w = 16, h = 12;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const float alpha = (x + y) % 3 == 0 ? 0.5f : 1.0f, grey = (x / 2 + y / 2) % 2 ? 1.0f : 0.0f;
            pixels.insert(pixels.end(), {grey * alpha, grey * alpha, grey * alpha, alpha});
        }
    Image picture = makeImage(w, h, 4, pixels);
    Mesh mesh = optimisedGridMesh(picture);
    Image colours = picture;
    simplifySerial(mesh, colours, w * h / 4);
    for (size_t v = 0; v < size_t(w) * h; ++v) {
        const float* c = &colours.pixels[v * 4];
        for (int k = 0; k < 4; ++k) CHECK((c[k] >= 0.0f && c[k] <= 1.0f));
        for (int k = 0; k < 3; ++k) CHECK(c[k] <= c[3]);
    }
}
