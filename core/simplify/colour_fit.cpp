#include "colour_fit.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

#include "edge_collapse.h"
#include "parallel.h"
#include "reconstruct.h"
#include "render.h"
#include "vertex_quadrics.h"

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

// The known samples as samples of the mesh: each lies in the first triangle (listTriangles'
// order) that holds it, edges included, weighted by its barycentric coordinates (exact
// orientations, divided in double). Found through a grid of cells about one sample each.
PixelSamples knownSampleHits(const Mesh& mesh, const std::vector<KnownSample>& samples) {
    PixelSamples located{listTriangles(mesh), {}, {}};
    const double pixels = double(mesh.width) * mesh.height;
    const int64_t cell = int64_t(std::max(1.0, std::ceil(std::sqrt(pixels / double(samples.size()))))) * kPositionOne;
    const int64_t columns = int64_t(mesh.width - 1) * kPositionOne / cell + 1,
                  rows = int64_t(mesh.height - 1) * kPositionOne / cell + 1;
    auto cellOf = [&](Position p) { return size_t(p.y / cell * columns + p.x / cell); };
    std::vector<uint32_t> cell_end(size_t(columns * rows) + 1, 0), in_cell(samples.size());
    for (const KnownSample& sample : samples) ++cell_end[cellOf(sample.place) + 1];
    for (size_t c = 1; c < cell_end.size(); ++c) cell_end[c] += cell_end[c - 1];
    std::vector<uint32_t> fill(cell_end.begin(), cell_end.end() - 1);
    for (uint32_t i = 0; i < samples.size(); ++i) in_cell[fill[cellOf(samples[i].place)]++] = i;

    std::vector<uint32_t> triangle_of(samples.size(), kNone);
    std::vector<SampleHit> hit_of(samples.size());
    for (uint32_t t = 0; t < located.triangles.size(); ++t) {
        const Triangle& tri = located.triangles[t];
        const Position p[3] = {positionOf(mesh, tri.v0), positionOf(mesh, tri.v1), positionOf(mesh, tri.v2)};
        const double area = double(positionOrient(p[0].x, p[0].y, p[1].x, p[1].y, p[2].x, p[2].y));
        const int64_t x0 = std::min({p[0].x, p[1].x, p[2].x}) / cell, x1 = std::max({p[0].x, p[1].x, p[2].x}) / cell;
        const int64_t y0 = std::min({p[0].y, p[1].y, p[2].y}) / cell, y1 = std::max({p[0].y, p[1].y, p[2].y}) / cell;
        for (int64_t cy = y0; cy <= y1; ++cy)
            for (int64_t cx = x0; cx <= x1; ++cx)
                for (uint32_t k = cell_end[size_t(cy * columns + cx)]; k < cell_end[size_t(cy * columns + cx) + 1]; ++k) {
                    const uint32_t i = in_cell[k];
                    if (triangle_of[i] != kNone) continue;
                    const Position q = samples[i].place;
                    int64_t w[3];
                    for (int j = 0; j < 3; ++j) {
                        const Position u = p[(j + 1) % 3], v = p[(j + 2) % 3];
                        w[j] = positionOrient(u.x, u.y, v.x, v.y, q.x, q.y);
                    }
                    if (w[0] < 0 || w[1] < 0 || w[2] < 0) continue;
                    triangle_of[i] = t;
                    hit_of[i] = {samples[i].vertex, {float(w[0] / area), float(w[1] / area), float(w[2] / area)}};
                }
    }
    // Grouped by triangle, as the fit walks them.
    located.ends.assign(located.triangles.size(), 0);
    for (uint32_t t : triangle_of)
        if (t != kNone) ++located.ends[t];
    for (size_t t = 1; t < located.ends.size(); ++t) located.ends[t] += located.ends[t - 1];
    located.hits.resize(located.ends.empty() ? 0 : located.ends.back());
    std::vector<uint32_t> next(located.triangles.size(), 0);
    for (size_t t = 1; t < next.size(); ++t) next[t] = located.ends[t - 1];
    for (uint32_t i = 0; i < samples.size(); ++i) {
        assert(triangle_of[i] != kNone);  // the simplification keeps the hull (edge_collapse.h)
        if (triangle_of[i] != kNone) located.hits[next[triangle_of[i]]++] = hit_of[i];
    }
    return located;
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

std::vector<KnownSample> knownSamplesOf(const Mesh& mesh) {
    std::vector<KnownSample> samples;
    const std::vector<bool> used = usedVertices(mesh);
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v)
        if (used[v]) samples.push_back({v, positionOf(mesh, v)});
    return samples;
}

void fitColours(const Mesh& mesh, const Image& picture, Image& colours, const std::vector<KnownSample>& known) {
    assert(picture.width == colours.width && picture.height == colours.height && picture.channels == colours.channels);
    const PixelSamples samples = known.empty() ? pixelSamples(mesh, colours) : knownSampleHits(mesh, known);
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
