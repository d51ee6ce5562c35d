#include "reconstruct.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "channel_count.h"
#include "degradation.h"
#include "parallel.h"
#include "pixel_vector.h"
#include "render.h"

namespace ddt {

namespace {

// Items are whole rows or runs of triangles: even a few are worth a thread each.
const size_t kGrain = 8;
// Runs of many triangles (locating samples sets up tables of the whole output's columns per
// run), but at least four runs a thread.
uint32_t trianglesPerRun(size_t triangles) {
    return uint32_t(std::clamp<size_t>(triangles / (4 * threadCount()), 4096, 65536));
}

double sigmaFor(double scale) { return scale <= 1.0 ? 0.0 : kFootprintSigma * std::sqrt(1.0 - 1.0 / (scale * scale)); }

int clampIndex(int i, int size) { return std::clamp(i, 0, size - 1); }

// The part of a residual beyond the tolerance: a surface whose degraded value lies within the
// input's quantisation interval is consistent with it, and chasing the rest would only
// sharpen the rounding noise.
float beyondTolerance(float residual, float tolerance) {
    return residual > tolerance ? residual - tolerance : residual < -tolerance ? residual + tolerance : 0.0f;
}

// The range vertex (x, y)'s values must stay in: its 3 × 3 input neighbourhood's, within
// [0, 1] for integer sample types; low and high get C values each. Scanned in row-major
// order with std::min and std::max, which keep the first of equal values (down to the sign of
// a zero). Worked out where it is needed rather than stored: two arrays the size of the input
// for nine loads per vertex and step.
template <uint32_t C>
void boundsAt(const Image& input, uint32_t x, uint32_t y, float* low, float* high) {
    const uint32_t x0 = x ? x - 1 : 0, y0 = y ? y - 1 : 0;
    const uint32_t columns = std::min(input.width - 1, x + 1) - x0 + 1, rows = std::min(input.height - 1, y + 1) - y0 + 1;
    // In locals, which the compiler keeps in registers (the arguments might alias the rows).
    float lo[C], hi[C];
    std::fill_n(lo, C, INFINITY);
    std::fill_n(hi, C, -INFINITY);
    auto scan = [&](uint32_t columns, uint32_t rows) {
        for (uint32_t j = 0; j < rows; ++j) {
            const float* row = input.row(y0 + j) + size_t(x0) * C;
            for (uint32_t i = 0; i < columns * C; ++i) {
                lo[i % C] = std::min(lo[i % C], row[i]);
                hi[i % C] = std::max(hi[i % C], row[i]);
            }
        }
    };
    if (columns == 3 && rows == 3)
        scan(3, 3);  // the same loop with constant bounds, unrolled: most vertices
    else
        scan(columns, rows);
    const bool unit = boundedToUnit(input.sample_type);
    for (uint32_t k = 0; k < C; ++k) {
        low[k] = unit ? std::max(lo[k], 0.0f) : lo[k];
        high[k] = unit ? std::min(hi[k], 1.0f) : hi[k];
    }
}

// Each triangle's partial sums of ⟨φ, g⟩ (projectOnBasis): per channel, its corners' hat
// functions φ_v0..φ_v2, then its edges' bubbles φ_e0..φ_e2.
constexpr uint32_t kSlotsPerTriangle = 6;

// A run of consecutive triangles and their supersamples, located by one task.
struct SampleRun {
    uint32_t first_triangle = 0, end_triangle = 0;
    std::vector<uint32_t> ends;      // per triangle of the run: where its samples end in `samples`
    std::vector<SampleHit> samples;  // triangle by triangle, row-major within one
};

// The supersamples grouped by triangle, and the triangles around each vertex and edge, so that
// every pass below is a gather: each output is written by one task, in a fixed order, and
// the result does not depend on how the work is split across threads.
struct SampleLayout {
    const std::vector<Triangle>& triangles;  // the locating renderer's
    std::vector<SampleRun> runs;             // the triangles in order, in runs of trianglesPerRun
    // Where each triangle's six partial sums go, 6 · triangle + n: the partial sums are kept
    // in the order that adds them up, so that adding them up reads them in sequence. Slots
    // [first_corner[v], first_corner[v + 1]) hold vertex v's corners in triangle order,
    // slots corners + 2 · e and the next edge e's first and second side (none: it stays 0).
    std::vector<uint32_t> slots;
    std::vector<uint32_t> first_corner;  // per vertex, + end
    uint32_t corners = 0;                // 3 · triangles

    // Calls f(triangle index, its samples' begin, end) for every triangle, a task per run.
    template <typename F>
    void forEachTriangle(F f) const {
        parallelFor(runs.size(), 1, [&](size_t begin, size_t end) {
            for (size_t r = begin; r < end; ++r) {
                const SampleRun& run = runs[r];
                const SampleHit* samples = run.samples.data();
                for (uint32_t t = run.first_triangle; t < run.end_triangle; ++t) {
                    const uint32_t i = t - run.first_triangle;
                    f(t, samples + (i ? run.ends[i - 1] : 0), samples + run.ends[i]);
                }
            }
        });
    }
};

SampleLayout layoutOf(const Mesh& mesh, const MeshRenderer& renderer, OutputSize sub_size) {
    SampleLayout layout{renderer.triangles(), {}, {}, {}, {}};
    const uint32_t triangles = uint32_t(layout.triangles.size());
    const uint32_t per_run = trianglesPerRun(triangles);
    layout.runs.resize((triangles + per_run - 1) / per_run);
    parallelFor(layout.runs.size(), 1, [&](size_t begin, size_t end) {
        for (size_t r = begin; r < end; ++r) {
            SampleRun& run = layout.runs[r];
            run.first_triangle = uint32_t(r * per_run);
            run.end_triangle = std::min(triangles, run.first_triangle + per_run);
            run.ends.resize(run.end_triangle - run.first_triangle);
            renderer.locateSamples(sub_size, run.first_triangle, run.end_triangle, run.samples, run.ends.data());
        }
    });
    layout.first_corner.assign(size_t(mesh.vertexCount()) + 1, 0);
    for (const Triangle& t : layout.triangles)
        for (uint32_t v : {t.v0, t.v1, t.v2}) ++layout.first_corner[v + 1];
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) layout.first_corner[v + 1] += layout.first_corner[v];
    layout.corners = 3 * triangles;
    layout.slots.resize(size_t(kSlotsPerTriangle) * triangles);
    std::vector<uint32_t> next_corner(layout.first_corner.begin(), layout.first_corner.end() - 1);
    std::vector<uint8_t> sides_seen(mesh.edgeCount(), 0);
    for (uint32_t t = 0; t < triangles; ++t) {
        const Triangle& tri = layout.triangles[t];
        const uint32_t vertices[3] = {tri.v0, tri.v1, tri.v2}, edges[3] = {tri.e0, tri.e1, tri.e2};
        for (uint32_t k = 0; k < 3; ++k) {
            layout.slots[kSlotsPerTriangle * t + k] = next_corner[vertices[k]]++;
            layout.slots[kSlotsPerTriangle * t + 3 + k] = layout.corners + 2 * edges[k] + sides_seen[edges[k]]++;
        }
    }
    return layout;
}

// The surface at every supersample (no clamping: the model sees the surface the solver moves).
void evaluate(const Surface& surface, const SampleLayout& layout, std::vector<float>& sub) {
    withChannelCount(surface.values.channels, [&](auto channels) {
        constexpr uint32_t c = decltype(channels)::value;
        const float* v = surface.values.pixels.data();
        const float* b = surface.bubbles.data();
        layout.forEachTriangle([&](uint32_t ti, const SampleHit* begin, const SampleHit* end) {
            const Triangle& t = layout.triangles[ti];
            const PixelVector<c> v0 = loadPixel<c>(v + size_t(t.v0) * c), v1 = loadPixel<c>(v + size_t(t.v1) * c),
                                 v2 = loadPixel<c>(v + size_t(t.v2) * c), b0 = loadPixel<c>(b + size_t(t.e0) * c),
                                 b1 = loadPixel<c>(b + size_t(t.e1) * c), b2 = loadPixel<c>(b + size_t(t.e2) * c);
            for (const SampleHit* s = begin; s != end; ++s) {
                const float* l = s->weights;
                const float q0 = 4 * l[1] * l[2], q1 = 4 * l[2] * l[0], q2 = 4 * l[0] * l[1];
                storePixel<c>(sub.data() + size_t(s->sample) * c, l[0] * v0 + l[1] * v1 + l[2] * v2 + q0 * b0 + q1 * b1 + q2 * b2);
            }
        });
    });
}

// ⟨φ_u, g⟩ for every vertex value and bubble u, g given at the supersamples: each triangle's
// six sums (its corners' hat functions, its edges' bubbles), then each vertex and edge adds
// those of its triangles and hands the sum (c floats) to at_vertex(v, sum) or at_edge(e, sum).
template <typename AtVertex, typename AtEdge>
void projectOnBasis(const std::vector<float>& g, uint32_t c, const SampleLayout& layout, uint32_t edges,
                    std::vector<float>& partial, AtVertex at_vertex, AtEdge at_edge) {
    // Zero at first: the second side of a hull edge is never written.
    if (partial.empty()) partial.assign((size_t(layout.corners) + 2 * size_t(edges)) * c, 0.0f);
    withChannelCount(c, [&](auto channels) {
        constexpr uint32_t cc = decltype(channels)::value;
        layout.forEachTriangle([&](uint32_t t, const SampleHit* begin, const SampleHit* end) {
            PixelVector<cc> sums[kSlotsPerTriangle] = {};
            for (const SampleHit* s = begin; s != end; ++s) {
                const float* l = s->weights;
                const float basis[kSlotsPerTriangle] = {l[0], l[1], l[2], 4 * l[1] * l[2], 4 * l[2] * l[0], 4 * l[0] * l[1]};
                const PixelVector<cc> value = loadPixel<cc>(g.data() + size_t(s->sample) * cc);
                for (uint32_t n = 0; n < kSlotsPerTriangle; ++n) sums[n] += basis[n] * value;
            }
            const uint32_t* slots = layout.slots.data() + size_t(t) * kSlotsPerTriangle;
            for (uint32_t n = 0; n < kSlotsPerTriangle; ++n) storePixel<cc>(partial.data() + size_t(slots[n]) * cc, sums[n]);
        });
        const uint32_t vertices = uint32_t(layout.first_corner.size() - 1);
        parallelFor(vertices, kGrain, [&](size_t begin, size_t end) {
            for (size_t v = begin; v < end; ++v) {
                PixelVector<cc> sum = {};
                for (uint32_t j = layout.first_corner[v]; j < layout.first_corner[v + 1]; ++j)
                    sum += loadPixel<cc>(partial.data() + size_t(j) * cc);
                float sums[4] = {};  // a callback reads c = cc of them
                storePixel<cc>(sums, sum);
                at_vertex(v, sums);
            }
        });
        const float* edge_sides = partial.data() + size_t(layout.corners) * cc;
        parallelFor(edges, kGrain, [&](size_t begin, size_t end) {
            for (size_t e = begin; e < end; ++e) {
                // From 0, as every sum here; the unwritten side of a hull edge adds 0.
                PixelVector<cc> sum = {};
                sum += loadPixel<cc>(edge_sides + 2 * e * cc);
                sum += loadPixel<cc>(edge_sides + (2 * e + 1) * cc);
                float sums[4] = {};
                storePixel<cc>(sums, sum);
                at_edge(e, sums);
            }
        });
    });
}

}  // namespace

bool boundedToUnit(SampleType type) { return type == SampleType::UInt8 || type == SampleType::UInt16; }

float quantisationTolerance(SampleType type) {
    switch (type) {
    case SampleType::UInt8: return 0.5f / 255.0f;
    case SampleType::UInt16: return 0.5f / 65535.0f;
    case SampleType::Half:
    case SampleType::Float: return 0.0f;
    }
    return 0.0f;
}

DegradationModel degradationFor(double scale_x, double scale_y) { return {sigmaFor(scale_x), sigmaFor(scale_y)}; }

std::vector<float> degradationTaps(double sigma) {
    if (sigma == 0.0) return {1.0f};
    const int radius = int(std::ceil(3.0 * sigma * kSupersampling));
    std::vector<double> weights(2 * radius + 1);
    double total = 0.0;
    for (int t = -radius; t <= radius; ++t) {
        const double d = double(t) / kSupersampling;
        total += weights[t + radius] = std::exp(-d * d / (2.0 * sigma * sigma));
    }
    std::vector<float> taps(weights.size());
    for (size_t i = 0; i < taps.size(); ++i) taps[i] = float(weights[i] / total);
    return taps;
}

Surface initialSurface(const Mesh& mesh, const Image& input) {
    const int w = int(input.width), h = int(input.height);
    const uint32_t c = input.channels;
    Surface surface{input, std::vector<float>(size_t(mesh.edgeCount()) * c)};
    auto at = [&](int x, int y) { return input.pixels.data() + (size_t(clampIndex(y, h)) * w + clampIndex(x, w)) * c; };
    parallelFor(mesh.edgeCount(), 4096, [&](size_t begin, size_t end) {
        for (size_t e = begin; e < end; ++e) {
            const int px = int(mesh.vertices[e].a % w), py = int(mesh.vertices[e].a / w);
            const int qx = int(mesh.vertices[e].b % w), qy = int(mesh.vertices[e].b / w);
            const float *p = at(px, py), *q = at(qx, qy);
            const float *before = at(2 * px - qx, 2 * py - qy), *after = at(2 * qx - px, 2 * qy - py);
            for (uint32_t k = 0; k < c; ++k)
                surface.bubbles[e * c + k] = (-before[k] + 9 * p[k] + 9 * q[k] - after[k]) / 16 - (p[k] + q[k]) / 2;
        }
    });
    return surface;
}

Surface reconstructSurface(const Mesh& mesh, const Image& input, const DegradationModel& model, uint32_t iterations) {
    if (model.identity() || iterations == 0) return initialSurface(mesh, input);
    return reconstructSurface(mesh, input, model, MeshRenderer(mesh, input), iterations);
}

namespace {

// The reconstruction; `release`, if given, is called once the mesh is no longer read (its
// arrays can make room for the solver's).
template <typename Release>
Surface reconstruct(const Mesh& mesh, const Image& input, const DegradationModel& model, const MeshRenderer& locator,
                    uint32_t iterations, Release release) {
    Surface surface = initialSurface(mesh, input);
    if (model.identity() || iterations == 0) return surface;  // D is the identity: already consistent
    const uint32_t c = input.channels;
    Degradation degradation(input.width, input.height, c, model);
    const SampleLayout layout = layoutOf(mesh, locator, {degradation.subWidth(), degradation.subHeight()});
    const float tolerance = quantisationTolerance(input.sample_type);
    const uint32_t edges = mesh.edgeCount();
    release();

    // SART's normalisers: ⟨φ_u, Dᵀ1⟩.
    std::vector<float> sub(size_t(degradation.subWidth()) * degradation.subHeight() * c), partial;
    std::vector<float> residual(input.pixels.size(), 1.0f);
    std::vector<float> vertex_weight(input.pixels.size()), edge_weight(surface.bubbles.size());
    degradation.transpose(residual, sub);
    projectOnBasis(
        sub, c, layout, edges, partial,
        [&](size_t vertex, const float* sum) { std::copy_n(sum, c, vertex_weight.data() + vertex * c); },
        [&](size_t edge, const float* sum) { std::copy_n(sum, c, edge_weight.data() + edge * c); });

    // Each step moves every unknown by ω·⟨φ_u, Dᵀr⟩ / ⟨φ_u, Dᵀ1⟩ as soon as its projection is
    // summed up (nothing else reads it): a vertex value within its bounds and premultiplied
    // colour at most alpha, a bubble where its normaliser is positive.
    std::vector<float>& v = surface.values.pixels;
    for (uint32_t step = 0; step < iterations; ++step) {
        evaluate(surface, layout, sub);
        degradation.apply(sub, residual);  // D(S), made the residual in place
        parallelFor(residual.size(), kGrain, [&](size_t begin, size_t end) {
            for (size_t i = begin; i < end; ++i) residual[i] = beyondTolerance(input.pixels[i] - residual[i], tolerance);
        });
        degradation.transpose(residual, sub);
        projectOnBasis(
            sub, c, layout, edges, partial,
            [&](size_t vertex, const float* step) {
                const size_t p = vertex * c;
                float low[4], high[4];
                const uint32_t x = uint32_t(vertex % input.width), y = uint32_t(vertex / input.width);
                withChannelCount(c, [&](auto channels) { boundsAt<decltype(channels)::value>(input, x, y, low, high); });
                for (uint32_t k = 0; k < c; ++k)
                    v[p + k] = std::clamp(v[p + k] + kRelaxation * step[k] / vertex_weight[p + k], low[k], high[k]);
                if (input.hasAlpha())
                    for (uint32_t k = 0; k + 1 < c; ++k) v[p + k] = std::min(v[p + k], v[p + c - 1]);
            },
            [&](size_t edge, const float* step) {
                for (uint32_t k = 0; k < c; ++k) {
                    const size_t i = edge * c + k;
                    if (edge_weight[i] > 0.0f) surface.bubbles[i] += kRelaxation * step[k] / edge_weight[i];
                }
            });
    }
    return surface;
}

}  // namespace

Surface reconstructSurface(const Mesh& mesh, const Image& input, const DegradationModel& model,
                           const MeshRenderer& locator, uint32_t iterations) {
    return reconstruct(mesh, input, model, locator, iterations, [] {});
}

Surface reconstructSurface(Mesh&& mesh, const Image& input, const DegradationModel& model, const MeshRenderer& locator,
                           uint32_t iterations) {
    return reconstruct(mesh, input, model, locator, iterations, [&] { mesh = {}; });
}

}  // namespace ddt
