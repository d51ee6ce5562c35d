#include "colour_fit.h"

#include <algorithm>
#include <cassert>
#include <vector>

#include "edge_collapse.h"
#include "parallel.h"
#include "reconstruct.h"
#include "render.h"

namespace ddt {

namespace {

constexpr double kStartWeight = 1e-3;
constexpr double kResidualShare = 1e-6;
constexpr int kMaxIterations = 64;

// The pixel centres as samples of the mesh: triangle t's weights are hits[ends[t − 1], ends[t]).
struct PixelSamples {
    std::vector<Triangle> triangles;
    std::vector<uint32_t> ends;
    std::vector<SampleHit> hits;

    // Calls visit(triangle, hit) for every sample, triangle by triangle.
    template <typename Visit>
    void forEach(Visit visit) const {
        for (size_t t = 0, i = 0; t < triangles.size(); ++t)
            for (; i < ends[t]; ++i) visit(triangles[t], hits[i]);
    }
};

PixelSamples pixelSamples(const Mesh& mesh, const Image& colours) {
    const MeshRenderer locator(mesh, colours);
    PixelSamples samples{locator.triangles(), std::vector<uint32_t>(locator.triangles().size()), {}};
    locator.locateSamples({colours.width, colours.height}, 0, uint32_t(samples.triangles.size()), samples.hits,
                          samples.ends.data());
    return samples;
}

// y = (LᵀL + μI) x, L the matrix of the samples' weights.
void applyNormal(const PixelSamples& samples, const std::vector<double>& x, std::vector<double>& y) {
    for (size_t v = 0; v < x.size(); ++v) y[v] = kStartWeight * x[v];
    samples.forEach([&](const Triangle& t, const SampleHit& hit) {
        const float* l = hit.weights;
        const double value = l[0] * x[t.v0] + l[1] * x[t.v1] + l[2] * x[t.v2];
        y[t.v0] += l[0] * value;
        y[t.v1] += l[1] * value;
        y[t.v2] += l[2] * value;
    });
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i) sum += a[i] * b[i];
    return sum;
}

// Channel k's colours by conjugate gradients on the normal equations, over the vertices
// `free` marks (1): the others' entries of the residual and the direction are held at zero,
// which is conjugate gradients on the free vertices' system with the fixed ones' colours given.
void fitChannel(const PixelSamples& samples, const std::vector<uint8_t>& free, const Image& picture, Image& colours,
                uint32_t k) {
    const uint32_t c = colours.channels;
    const size_t vertices = size_t(colours.width) * colours.height;
    std::vector<double> x(vertices), rhs(vertices), residual(vertices), direction(vertices), product(vertices);
    for (size_t v = 0; v < vertices; ++v) {
        x[v] = colours.pixels[v * c + k];
        rhs[v] = kStartWeight * x[v];
    }
    samples.forEach([&](const Triangle& t, const SampleHit& hit) {
        const double pixel = picture.pixels[size_t(hit.sample) * c + k];
        rhs[t.v0] += hit.weights[0] * pixel;
        rhs[t.v1] += hit.weights[1] * pixel;
        rhs[t.v2] += hit.weights[2] * pixel;
    });
    applyNormal(samples, x, product);
    for (size_t v = 0; v < vertices; ++v) residual[v] = direction[v] = free[v] ? rhs[v] - product[v] : 0.0;
    double norm = dot(residual, residual);
    const double stop = dot(rhs, rhs) * kResidualShare * kResidualShare;
    for (int iteration = 0; iteration < kMaxIterations && norm > stop; ++iteration) {
        applyNormal(samples, direction, product);
        const double step = norm / dot(direction, product);
        for (size_t v = 0; v < vertices; ++v) {
            x[v] += step * direction[v];
            residual[v] -= free[v] ? step * product[v] : 0.0;
        }
        const double next = dot(residual, residual);
        for (size_t v = 0; v < vertices; ++v) direction[v] = residual[v] + next / norm * direction[v];
        norm = next;
    }
    const bool bounded = boundedToUnit(colours.sample_type);
    for (size_t v = 0; v < vertices; ++v) colours.pixels[v * c + k] = bounded ? float(std::clamp(x[v], 0.0, 1.0)) : float(x[v]);
}

}  // namespace

void fitColours(const Mesh& mesh, const Image& picture, Image& colours) {
    assert(picture.width == colours.width && picture.height == colours.height && picture.channels == colours.channels);
    const PixelSamples samples = pixelSamples(mesh, colours);
    std::vector<uint8_t> free(size_t(colours.width) * colours.height, 1);
    if (mesh.locked_sides)
        for (uint32_t v = 0; v < mesh.vertexCount(); ++v) free[v] = !lockedVertex(mesh, v);
    parallelFor(colours.channels, 1, [&](size_t begin, size_t end) {
        for (size_t k = begin; k < end; ++k) fitChannel(samples, free, picture, colours, uint32_t(k));
    });
    if (!colours.hasAlpha()) return;
    const uint32_t c = colours.channels;
    for (size_t v = 0; v < size_t(colours.width) * colours.height; ++v)
        for (uint32_t k = 0; k + 1 < c; ++k) colours.pixels[v * c + k] = std::min(colours.pixels[v * c + k], colours.pixels[v * c + c - 1]);
}

}  // namespace ddt
