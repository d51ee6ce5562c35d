#include "reconstruct.h"

#include <algorithm>
#include <cmath>

#include "channel_count.h"
#include "degradation.h"
#include "divide_by.h"
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

// For `mixed`, the footprint's width (its bicubic part is at width 1, as a named filter's).
double widthFor(AssumedKernel kernel, double scale) {
    if (scale <= 1.0) return 0.0;
    const bool footprint = kernel == AssumedKernel::footprint || kernel == AssumedKernel::mixed;
    return footprint ? std::sqrt(1.0 - 1.0 / (scale * scale)) : 1.0;
}

// One kernel's taps at a positive width (degradationTaps).
std::vector<float> kernelTaps(AssumedKernel kernel, double width) {
    const int radius = int(std::ceil(kernelSupport(kernel) * width * kSupersampling));
    std::vector<double> weights;
    for (int t = -radius; t <= radius; ++t) weights.push_back(kernelWeight(kernel, double(t) / kSupersampling / width));
    // Zero taps at the ends (a kernel's support falling on a tap) only cost work.
    while (weights.size() > 1 && weights.front() == 0.0) {
        weights.erase(weights.begin());
        weights.pop_back();
    }
    double total = 0.0;
    for (double w : weights) total += w;
    std::vector<float> taps(weights.size());
    for (size_t i = 0; i < taps.size(); ++i) taps[i] = float(weights[i] / total);
    return taps;
}

int clampIndex(int i, int size) { return std::clamp(i, 0, size - 1); }

// The part of a residual beyond the tolerance: a surface whose degraded value lies within the
// input's quantisation interval is consistent with it, and chasing the rest would only
// sharpen the rounding noise.
float beyondTolerance(float residual, float tolerance) {
    return residual > tolerance ? residual - tolerance : residual < -tolerance ? residual + tolerance : 0.0f;
}

// The range each vertex value must stay in: its 3 × 3 input neighbourhood's, within [0, 1]
// for integer sample types.
struct Bounds {
    std::vector<float> low, high;
};

// Separable: the 3-wide range of each row, then of three rows of those. std::min and std::max
// keep the first of equal values, so this picks the same value (down to the sign of a zero)
// as a scan of the 3 × 3 pixels in row-major order.
Bounds boundsOf(const Image& input) {
    const uint32_t w = input.width, h = input.height, c = input.channels;
    const size_t row_floats = size_t(w) * c;
    const bool integer = boundedToUnit(input.sample_type);
    Bounds bounds{std::vector<float>(input.pixels.size()), std::vector<float>(input.pixels.size())};
    parallelFor(h, kGrain, [&](size_t begin, size_t end) {
        // The rows' own ranges, for rows [first, last] of this task.
        const size_t first = begin ? begin - 1 : 0, last = std::min<size_t>(h - 1, end);
        std::vector<float> row_low((last - first + 1) * row_floats), row_high(row_low.size());
        for (size_t y = first; y <= last; ++y) {
            const float* row = input.row(uint32_t(y));
            float* low = row_low.data() + (y - first) * row_floats;
            float* high = row_high.data() + (y - first) * row_floats;
            for (uint32_t x = 0; x < w; ++x)
                for (uint32_t k = 0; k < c; ++k) {
                    float lo = INFINITY, hi = -INFINITY;
                    for (uint32_t nx = x ? x - 1 : 0; nx <= std::min(w - 1, x + 1); ++nx) {
                        lo = std::min(lo, row[nx * c + k]);
                        hi = std::max(hi, row[nx * c + k]);
                    }
                    low[x * c + k] = lo;
                    high[x * c + k] = hi;
                }
        }
        for (size_t y = begin; y < end; ++y)
            for (size_t i = 0; i < row_floats; ++i) {
                float lo = INFINITY, hi = -INFINITY;
                for (size_t ny = y ? y - 1 : 0; ny <= std::min<size_t>(h - 1, y + 1); ++ny) {
                    lo = std::min(lo, row_low[(ny - first) * row_floats + i]);
                    hi = std::max(hi, row_high[(ny - first) * row_floats + i]);
                }
                if (integer) {
                    lo = std::max(lo, 0.0f);
                    hi = std::min(hi, 1.0f);
                }
                bounds.low[y * row_floats + i] = lo;
                bounds.high[y * row_floats + i] = hi;
            }
    });
    return bounds;
}

// Each triangle's partial sums of ⟨φ, g⟩ (projectOnBasis): per channel, its corners' hat
// functions φ_v0..φ_v2, then its edges' bubbles φ_e0..φ_e2.
constexpr uint32_t kSlotsPerTriangle = 6;
// A partial sum that goes straight to its vertex's or edge's total (see SampleRun::shared).
constexpr uint32_t kOwned = UINT32_MAX;

// A triangle touching a shared vertex or edge, and where its partial sums go: the slot of the
// shared sums, or kOwned.
struct SharedSlots {
    uint32_t triangle;
    uint32_t slots[kSlotsPerTriangle];
};

// A run of consecutive triangles and their supersamples, located by one task.
struct SampleRun {
    uint32_t first_triangle = 0, end_triangle = 0;
    std::vector<uint32_t> ends;      // per triangle of the run: where its samples end in `samples`
    std::vector<SampleHit> samples;  // triangle by triangle, row-major within one
    // The run's triangles that touch a vertex or edge of another run too, in order. Their
    // partial sums for those are kept apart and added up after all runs, in triangle order.
    std::vector<SharedSlots> shared;
};

// The supersamples grouped by triangle, so that every pass below is a gather or writes only
// what one task owns: each sum is added up in a fixed order, and the result does not depend
// on how the work is split across threads. A vertex or edge whose triangles all lie in one
// run gets them added straight into its total by that run, in triangle order; one that
// several runs touch (along the runs' borders: a few rows of the mesh) gets its partial sums
// in slots and added up, in triangle order too, once all runs are done.
struct SampleLayout {
    const std::vector<Triangle>& triangles;  // the locating renderer's
    std::vector<SampleRun> runs;             // the triangles in order, in runs of trianglesPerRun
    // The shared vertices, ascending, with their corners' slots [first_slot[i], first_slot[i + 1]);
    // the shared edges, ascending, edge i's first and second side at slots edge_slots + 2i (+1).
    std::vector<uint32_t> shared_vertices, first_slot, shared_edges;
    uint32_t edge_slots = 0, slots = 0;

    // Calls f(triangle index, its samples' begin, end, its shared slots or null) for every
    // triangle, a task per run.
    template <typename F>
    void forEachTriangle(F f) const {
        parallelFor(runs.size(), 1, [&](size_t begin, size_t end) {
            for (size_t r = begin; r < end; ++r) {
                const SampleRun& run = runs[r];
                const SampleHit* samples = run.samples.data();
                auto shared = run.shared.begin();  // the next shared triangle
                for (uint32_t t = run.first_triangle; t < run.end_triangle; ++t) {
                    const uint32_t i = t - run.first_triangle;
                    const SharedSlots* slots = nullptr;
                    if (shared != run.shared.end() && shared->triangle == t) slots = &*shared++;
                    f(t, samples + (i ? run.ends[i - 1] : 0), samples + run.ends[i], slots);
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
    // Which vertices and edges more than one run touches: their index among the shared ones
    // (kOwned for the others), from the run each was first seen in (kNone: not seen yet).
    const uint32_t vertices = mesh.vertexCount(), edges = mesh.edgeCount();
    std::vector<uint32_t> vertex_index(vertices, kOwned), edge_index(edges, kOwned);
    {
        std::vector<uint32_t> vertex_run(vertices, kNone), edge_run(edges, kNone);
        auto see = [](uint32_t& first_run, uint32_t& index, uint32_t run) {
            if (first_run == kNone) first_run = run;
            else if (first_run != run) index = 0;  // numbered below
        };
        for (uint32_t t = 0; t < triangles; ++t) {
            const Triangle& tri = layout.triangles[t];
            const uint32_t run = t / per_run;
            for (uint32_t v : {tri.v0, tri.v1, tri.v2}) see(vertex_run[v], vertex_index[v], run);
            for (uint32_t e : {tri.e0, tri.e1, tri.e2}) see(edge_run[e], edge_index[e], run);
        }
    }
    for (uint32_t v = 0; v < vertices; ++v)
        if (vertex_index[v] != kOwned) {
            vertex_index[v] = uint32_t(layout.shared_vertices.size());
            layout.shared_vertices.push_back(v);
        }
    for (uint32_t e = 0; e < edges; ++e)
        if (edge_index[e] != kOwned) {
            edge_index[e] = uint32_t(layout.shared_edges.size());
            layout.shared_edges.push_back(e);
        }
    // Slots: the shared vertices' corners in triangle order, then the shared edges' sides.
    layout.first_slot.assign(layout.shared_vertices.size() + 1, 0);
    for (const Triangle& t : layout.triangles)
        for (uint32_t v : {t.v0, t.v1, t.v2})
            if (vertex_index[v] != kOwned) ++layout.first_slot[vertex_index[v] + 1];
    for (size_t i = 0; i < layout.shared_vertices.size(); ++i) layout.first_slot[i + 1] += layout.first_slot[i];
    layout.edge_slots = layout.first_slot.back();
    layout.slots = layout.edge_slots + 2 * uint32_t(layout.shared_edges.size());
    std::vector<uint32_t> next_corner(layout.first_slot.begin(), layout.first_slot.end() - 1);
    std::vector<uint8_t> sides_seen(layout.shared_edges.size(), 0);
    for (SampleRun& run : layout.runs)
        for (uint32_t t = run.first_triangle; t < run.end_triangle; ++t) {
            const Triangle& tri = layout.triangles[t];
            const uint32_t corners[3] = {vertex_index[tri.v0], vertex_index[tri.v1], vertex_index[tri.v2]};
            const uint32_t sides[3] = {edge_index[tri.e0], edge_index[tri.e1], edge_index[tri.e2]};
            SharedSlots shared{t, {kOwned, kOwned, kOwned, kOwned, kOwned, kOwned}};
            bool any = false;
            for (uint32_t k = 0; k < 3; ++k) {
                if (corners[k] != kOwned) shared.slots[k] = next_corner[corners[k]]++, any = true;
                if (sides[k] != kOwned)
                    shared.slots[3 + k] = layout.edge_slots + 2 * sides[k] + sides_seen[sides[k]]++, any = true;
            }
            if (any) run.shared.push_back(shared);
        }
    return layout;
}

// The surface at every supersample (no clamping: the model sees the surface the solver moves).
void evaluate(const Surface& surface, const SampleLayout& layout, std::vector<float>& sub) {
    withChannelCount(surface.values.channels, [&](auto channels) {
        constexpr uint32_t c = decltype(channels)::value;
        const float* v = surface.values.pixels.data();
        const float* b = surface.bubbles.data();
        layout.forEachTriangle([&](uint32_t ti, const SampleHit* begin, const SampleHit* end, const SharedSlots*) {
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

// What projectOnBasis works in, kept across calls: the shared partial sums and every
// vertex's and edge's total (c floats each).
struct Projection {
    std::vector<float> partial, vertex_sums, edge_sums;
};

// ⟨φ_u, g⟩ for every vertex value and bubble u, g given at the supersamples: each triangle's
// six sums (its corners' hat functions, its edges' bubbles) are added into its vertices' and
// edges' totals (SampleLayout), which go to at_vertex(v, sum) or at_edge(e, sum) (c floats).
template <typename AtVertex, typename AtEdge>
void projectOnBasis(const std::vector<float>& g, uint32_t c, const SampleLayout& layout, uint32_t vertices,
                    uint32_t edges, Projection& work, AtVertex at_vertex, AtEdge at_edge) {
    // Every total from 0 (the gather below leaves them so for the next call); so is every
    // shared slot, as the second side of a hull edge is never written.
    if (work.vertex_sums.empty()) work.vertex_sums.assign(size_t(vertices) * c, 0.0f);
    if (work.edge_sums.empty()) work.edge_sums.assign(size_t(edges) * c, 0.0f);
    work.partial.assign(size_t(layout.slots) * c, 0.0f);
    withChannelCount(c, [&](auto channels) {
        constexpr uint32_t cc = decltype(channels)::value;
        float* const vertex_sums = work.vertex_sums.data();
        float* const edge_sums = work.edge_sums.data();
        auto add = [](float* total, PixelVector<cc> value) { storePixel<cc>(total, loadPixel<cc>(total) + value); };
        layout.forEachTriangle([&](uint32_t t, const SampleHit* begin, const SampleHit* end, const SharedSlots* slots) {
            PixelVector<cc> sums[kSlotsPerTriangle] = {};
            for (const SampleHit* s = begin; s != end; ++s) {
                const float* l = s->weights;
                const float basis[kSlotsPerTriangle] = {l[0], l[1], l[2], 4 * l[1] * l[2], 4 * l[2] * l[0], 4 * l[0] * l[1]};
                const PixelVector<cc> value = loadPixel<cc>(g.data() + size_t(s->sample) * cc);
                for (uint32_t n = 0; n < kSlotsPerTriangle; ++n) sums[n] += basis[n] * value;
            }
            const Triangle& tri = layout.triangles[t];
            const uint32_t targets[kSlotsPerTriangle] = {tri.v0, tri.v1, tri.v2, tri.e0, tri.e1, tri.e2};
            for (uint32_t n = 0; n < kSlotsPerTriangle; ++n) {
                if (slots && slots->slots[n] != kOwned)
                    storePixel<cc>(work.partial.data() + size_t(slots->slots[n]) * cc, sums[n]);
                else
                    add((n < 3 ? vertex_sums : edge_sums) + size_t(targets[n]) * cc, sums[n]);
            }
        });
        // The shared totals, each from 0 in triangle order (an edge: its first side, then its second).
        parallelFor(layout.shared_vertices.size(), kGrain, [&](size_t begin, size_t end) {
            for (size_t i = begin; i < end; ++i) {
                PixelVector<cc> sum = {};
                for (uint32_t j = layout.first_slot[i]; j < layout.first_slot[i + 1]; ++j)
                    sum += loadPixel<cc>(work.partial.data() + size_t(j) * cc);
                storePixel<cc>(vertex_sums + size_t(layout.shared_vertices[i]) * cc, sum);
            }
        });
        parallelFor(layout.shared_edges.size(), kGrain, [&](size_t begin, size_t end) {
            for (size_t i = begin; i < end; ++i) {
                PixelVector<cc> sum = {};
                sum += loadPixel<cc>(work.partial.data() + size_t(layout.edge_slots + 2 * i) * cc);
                sum += loadPixel<cc>(work.partial.data() + size_t(layout.edge_slots + 2 * i + 1) * cc);
                storePixel<cc>(edge_sums + size_t(layout.shared_edges[i]) * cc, sum);
            }
        });
        parallelFor(vertices, kGrain, [&](size_t begin, size_t end) {
            for (size_t v = begin; v < end; ++v) {
                at_vertex(v, vertex_sums + v * cc);
                std::fill_n(vertex_sums + v * cc, cc, 0.0f);
            }
        });
        parallelFor(edges, kGrain, [&](size_t begin, size_t end) {
            for (size_t e = begin; e < end; ++e) {
                at_edge(e, edge_sums + e * cc);
                std::fill_n(edge_sums + e * cc, cc, 0.0f);
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

DegradationModel degradationFor(double scale_x, double scale_y, AssumedKernel kernel) {
    return {kernel, widthFor(kernel, scale_x), widthFor(kernel, scale_y)};
}

std::vector<float> degradationTaps(AssumedKernel kernel, double width) {
    if (width == 0.0) return {1.0f};
    if (kernel != AssumedKernel::mixed) return kernelTaps(kernel, width);
    // Both normalised tap sets centred on one another, the shorter padded with zeros.
    const std::vector<float> footprint = kernelTaps(AssumedKernel::footprint, width),
                             bicubic = kernelTaps(AssumedKernel::bicubic, 1.0);
    const size_t size = std::max(footprint.size(), bicubic.size());
    auto tap = [size](const std::vector<float>& taps, size_t i) {
        const size_t offset = (size - taps.size()) / 2;
        return i >= offset && i - offset < taps.size() ? taps[i - offset] : 0.0f;
    };
    std::vector<float> taps(size);
    for (size_t i = 0; i < size; ++i)
        taps[i] = float(kMixedFootprintShare * tap(footprint, i) + (1.0 - kMixedFootprintShare) * tap(bicubic, i));
    return taps;
}

Surface initialSurface(const Mesh& mesh, const Image& input) {
    const int w = int(input.width), h = int(input.height);
    const uint32_t c = input.channels;
    Surface surface{input, std::vector<float>(size_t(mesh.edgeCount()) * c)};
    const DivideBy by_width(input.width);  // a vertex's row without a division instruction (a grid is ≥ 2 wide)
    auto row = [&](uint32_t vertex) { return int(by_width.quotient(vertex)); };
    withChannelCount(c, [&](auto channels) {
        constexpr uint32_t cc = decltype(channels)::value;
        auto at = [&](int x, int y) {
            return loadPixel<cc>(input.pixels.data() + (size_t(clampIndex(y, h)) * w + clampIndex(x, w)) * cc);
        };
        parallelFor(mesh.edgeCount(), 4096, [&](size_t begin, size_t end) {
            for (size_t e = begin; e < end; ++e) {
                const int py = row(mesh.vertices[e].a), px = int(mesh.vertices[e].a) - py * w;
                const int qy = row(mesh.vertices[e].b), qx = int(mesh.vertices[e].b) - qy * w;
                const PixelVector<cc> p = at(px, py), q = at(qx, qy);
                const PixelVector<cc> before = at(2 * px - qx, 2 * py - qy), after = at(2 * qx - px, 2 * qy - py);
                storePixel<cc>(surface.bubbles.data() + e * cc,
                               (-before + 9.0f * p + 9.0f * q - after) / 16.0f - (p + q) / 2.0f);
            }
        });
    });
    return surface;
}

Surface reconstructSurface(const Mesh& mesh, const Image& input, const DegradationModel& model, uint32_t iterations) {
    if (model.identity() || iterations == 0) return initialSurface(mesh, input);
    return reconstructSurface(mesh, input, model, MeshRenderer(mesh, input), iterations);
}

namespace {

// The reconstruction; `release()` is called once the mesh is no longer read, so that a caller
// that gives the mesh up can free it before the solver's arrays are made.
template <typename Release>
Surface reconstruct(const Mesh& mesh, const Image& input, const DegradationModel& model, const MeshRenderer& locator,
                    uint32_t iterations, Release release) {
    Surface surface = initialSurface(mesh, input);
    if (model.identity() || iterations == 0) return surface;  // D is the identity: already consistent
    const uint32_t c = input.channels;
    Degradation degradation(input.width, input.height, c, model);
    const SampleLayout layout = layoutOf(mesh, locator, {degradation.subWidth(), degradation.subHeight()});
    const float tolerance = quantisationTolerance(input.sample_type);
    const uint32_t vertices = mesh.vertexCount(), edges = mesh.edgeCount();
    release();
    const Bounds bounds = boundsOf(input);

    // SART's normalisers: ⟨φ_u, Dᵀ1⟩, the same for every channel (the same operations on the
    // same values), so worked out on one.
    std::vector<float> vertex_weight(vertices), edge_weight(edges);
    {
        Degradation one_channel(input.width, input.height, 1, model);
        std::vector<float> ones(size_t(input.width) * input.height, 1.0f), sub;
        one_channel.transpose(ones, sub);
        Projection projection;
        projectOnBasis(
            sub, 1, layout, vertices, edges, projection, [&](size_t vertex, const float* sum) { vertex_weight[vertex] = *sum; },
            [&](size_t edge, const float* sum) { edge_weight[edge] = *sum; });
    }
    std::vector<float> sub(size_t(degradation.subWidth()) * degradation.subHeight() * c), residual(input.pixels.size());
    Projection projection;

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
            sub, c, layout, vertices, edges, projection,
            [&](size_t vertex, const float* step) {
                const size_t p = vertex * c;
                for (uint32_t k = 0; k < c; ++k)
                    v[p + k] = std::clamp(v[p + k] + kRelaxation * step[k] / vertex_weight[vertex], bounds.low[p + k],
                                          bounds.high[p + k]);
                if (input.hasAlpha())
                    for (uint32_t k = 0; k + 1 < c; ++k) v[p + k] = std::min(v[p + k], v[p + c - 1]);
            },
            [&](size_t edge, const float* step) {
                for (uint32_t k = 0; k < c; ++k) {
                    const size_t i = edge * c + k;
                    if (edge_weight[edge] > 0.0f) surface.bubbles[i] += kRelaxation * step[k] / edge_weight[edge];
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
