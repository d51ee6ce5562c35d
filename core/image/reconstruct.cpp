#include "reconstruct.h"

#include <algorithm>
#include <cmath>

#include "channel_count.h"
#include "degradation.h"
#include "divide_by.h"
#include "parallel.h"
#include "pixel_vector.h"
#include "supersample_lattice.h"

namespace ddt {

namespace {

// Items are whole rows: even a few are worth a thread each.
const size_t kGrain = 8;
// Items are vertices or edges.
const size_t kElementGrain = 4096;

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
    UninitialisedVector<float> low, high;  // first written by the parallel pass
};

// Separable: the 3-wide range of each row, then of three rows of those, a pixel's channels at
// once. Each min and max keeps the first of equal values (as std::min and std::max do), so
// this picks the same value (down to the sign of a zero) as a scan of the 3 × 3 pixels in
// row-major order.
template <uint32_t C>
Bounds boundsWith(const Image& input) {
    const uint32_t w = input.width, h = input.height;
    const bool integer = boundedToUnit(input.sample_type);
    Bounds bounds{UninitialisedVector<float>(input.pixels.size()), UninitialisedVector<float>(input.pixels.size())};
    auto lower = [](PixelVector<C> a, PixelVector<C> b) { return b < a ? b : a; };
    auto higher = [](PixelVector<C> a, PixelVector<C> b) { return a < b ? b : a; };
    parallelFor(h, kGrain, [&](size_t begin, size_t end) {
        // The rows' own ranges, for rows [first, last] of this task.
        const size_t first = begin ? begin - 1 : 0, last = std::min<size_t>(h - 1, end);
        std::vector<PixelVector<C>> row_low((last - first + 1) * w), row_high(row_low.size());
        for (size_t y = first; y <= last; ++y) {
            const float* row = input.row(uint32_t(y));
            PixelVector<C>* low = row_low.data() + (y - first) * w;
            PixelVector<C>* high = row_high.data() + (y - first) * w;
            for (uint32_t x = 0; x < w; ++x) {
                PixelVector<C> lo = loadPixel<C>(row + (x ? x - 1 : 0) * C), hi = lo;
                for (uint32_t nx = x ? x : 1; nx <= std::min(w - 1, x + 1); ++nx) {
                    lo = lower(lo, loadPixel<C>(row + nx * C));
                    hi = higher(hi, loadPixel<C>(row + nx * C));
                }
                low[x] = lo;
                high[x] = hi;
            }
        }
        for (size_t y = begin; y < end; ++y) {
            const size_t top = (y ? y - 1 : 0) - first, bottom = std::min<size_t>(h - 1, y + 1) - first;
            for (uint32_t x = 0; x < w; ++x) {
                PixelVector<C> lo = row_low[top * w + x], hi = row_high[top * w + x];
                for (size_t ny = top + 1; ny <= bottom; ++ny) {
                    lo = lower(lo, row_low[ny * w + x]);
                    hi = higher(hi, row_high[ny * w + x]);
                }
                if (integer) {
                    lo = higher(lo, PixelVector<C>{} + 0.0f);
                    hi = lower(hi, PixelVector<C>{} + 1.0f);
                }
                storePixel<C>(bounds.low.data() + (y * w + x) * C, lo);
                storePixel<C>(bounds.high.data() + (y * w + x) * C, hi);
            }
        }
    });
    return bounds;
}

Bounds boundsOf(const Image& input) {
    Bounds bounds;
    withChannelCount(input.channels, [&](auto channels) { bounds = boundsWith<decltype(channels)::value>(input); });
    return bounds;
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
    Surface surface{input, UninitialisedVector<float>(size_t(mesh.edgeCount()) * c)};
    const DivideBy by_width(input.width);  // a vertex's row without a division instruction (a grid is ≥ 2 wide)
    auto row = [&](uint32_t vertex) { return int(by_width.quotient(vertex)); };
    withChannelCount(c, [&](auto channels) {
        constexpr uint32_t cc = decltype(channels)::value;
        auto at = [&](int x, int y) {
            return loadPixel<cc>(input.pixels.data() + (size_t(clampIndex(y, h)) * w + clampIndex(x, w)) * cc);
        };
        parallelFor(mesh.edgeCount(), kElementGrain, [&](size_t begin, size_t end) {
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

namespace {

// SART on the lattice from `surface`, the initial one.
Surface solve(const SupersampleLattice& lattice, Surface surface, const Image& input, const DegradationModel& model,
              uint32_t iterations) {
    const uint32_t c = input.channels, vertices = input.width * input.height, edges = lattice.edgeCount();
    Degradation degradation(input.width, input.height, c, model);
    const float tolerance = quantisationTolerance(input.sample_type);
    const Bounds bounds = boundsOf(input);
    // Left uninitialised, so that their pages are first touched by the parallel passes.
    UninitialisedVector<float> sub(size_t(lattice.subWidth()) * lattice.subHeight() * c), residual(input.pixels.size());

    // SART's normalisers ⟨φ_u, Dᵀ1⟩, the same for every channel (the same operations on the
    // same values), so worked out on one; kept as each unknown's step per unit of projection,
    // ω / ⟨φ_u, Dᵀ1⟩ (0 for a bubble whose normaliser is not positive: it stays).
    UninitialisedVector<float> vertex_scale(vertices), edge_scale(edges);
    std::fill_n(residual.data(), vertices, 1.0f);
    Degradation(input.width, input.height, 1, model).transpose(residual.data(), sub.data());
    lattice.project<1>(
        sub.data(), [&](size_t vertex, float sum) { vertex_scale[vertex] = kRelaxation / sum; },
        [&](size_t edge, float sum) { edge_scale[edge] = sum > 0.0f ? kRelaxation / sum : 0.0f; });

    // Each step moves every unknown by ω·⟨φ_u, Dᵀr⟩ / ⟨φ_u, Dᵀ1⟩ as soon as its projection is
    // summed up (nothing else reads it): a vertex value within its bounds and premultiplied
    // colour at most alpha.
    float* const v = surface.values.pixels.data();
    float* const b = surface.bubbles.data();
    for (uint32_t step = 0; step < iterations; ++step) {
        lattice.evaluate(v, b, c, sub.data());
        degradation.apply(sub.data(), residual.data());  // D(S), made the residual in place
        parallelFor(residual.size(), kElementGrain, [&](size_t begin, size_t end) {
            for (size_t i = begin; i < end; ++i) residual[i] = beyondTolerance(input.pixels[i] - residual[i], tolerance);
        });
        degradation.transpose(residual.data(), sub.data());
        withChannelCount(c, [&](auto channels) {
            constexpr uint32_t cc = decltype(channels)::value;
            lattice.project<cc>(
                sub.data(),
                [&](size_t vertex, PixelVector<cc> step) {
                    const size_t p = vertex * cc;
                    PixelVector<cc> moved = loadPixel<cc>(v + p) + vertex_scale[vertex] * step;
                    const PixelVector<cc> low = loadPixel<cc>(bounds.low.data() + p), high = loadPixel<cc>(bounds.high.data() + p);
                    moved = moved < low ? low : moved;  // std::clamp, lane by lane
                    moved = high < moved ? high : moved;
                    storePixel<cc>(v + p, moved);
                    if (input.hasAlpha())
                        for (uint32_t k = 0; k + 1 < cc; ++k) v[p + k] = std::min(v[p + k], v[p + cc - 1]);
                },
                [&](size_t edge, PixelVector<cc> step) {
                    storePixel<cc>(b + edge * cc, loadPixel<cc>(b + edge * cc) + edge_scale[edge] * step);
                });
        });
    }
    return surface;
}

}  // namespace

Surface reconstructSurface(const Mesh& mesh, const Image& input, const DegradationModel& model, uint32_t iterations) {
    Surface surface = initialSurface(mesh, input);
    if (model.identity() || iterations == 0) return surface;  // D is the identity: already consistent
    const std::vector<Triangle> triangles = listTriangles(mesh);
    const SupersampleLattice lattice(mesh.width, mesh.height, input.channels, mesh.vertices, triangles);
    return solve(lattice, std::move(surface), input, model, iterations);
}

Surface reconstructSurface(Mesh&& mesh, const Image& input, const DegradationModel& model,
                           const std::vector<Triangle>& triangles, uint32_t iterations) {
    mesh.neighbours = {};  // only the edges' vertices are read from here on
    Surface surface = initialSurface(mesh, input);
    if (model.identity() || iterations == 0) return surface;
    const SupersampleLattice lattice(mesh.width, mesh.height, input.channels, std::move(mesh.vertices), triangles);
    mesh = {};
    return solve(lattice, std::move(surface), input, model, iterations);
}

}  // namespace ddt
