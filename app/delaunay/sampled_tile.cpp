#include "sampled_tile.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "nearest_fill.h"
#include "point_mesh.h"
#include "raster.h"
#include "sampled_render.h"

namespace ddt {

namespace {

constexpr float kUncovered = std::numeric_limits<float>::quiet_NaN();

void clearRows(const RenderWindow& window, uint32_t channels, float* rows, size_t row_stride) {
    for (uint32_t y = 0; y < window.height(); ++y)
        std::fill_n(rows + y * row_stride, size_t(window.width()) * channels, kUncovered);
}

// A tile's optimised sample mesh, rendered like the whole image's (core/delaunay/sampled_render.h)
// but a window at a time; the pixels of its output outside the hull were filled when it was made.
class SampledSurface final : public HostSurface {
public:
    // `frame`'s crop offset is the mesh's: its samples' bounds may reach past the crop its
    // windows name (KnownSamples::samplesAlongBorder, samplesBreaking).
    SampledSurface(Image values, const Mesh& mesh, const RenderWindow& frame)
        : values_(std::move(values)),
          renderer_(mesh, values_),
          edges_(hullEdgesOf(mesh, frame)),
          snapped_(!mesh.positions.empty()),
          crop_x_(frame.crop_x),
          crop_y_(frame.crop_y) {}
    SampledSurface(const SampledSurface&) = delete;  // renderer_ refers to values_
    SampledSurface& operator=(const SampledSurface&) = delete;

    // The surface's samples of `window` without the nearest fill: NaN outside the hull.
    void renderHull(const RenderWindow& window, float* rows, size_t row_stride) const {
        clearRows(window, values_.channels, rows, row_stride);
        RenderWindow placed = window;
        placed.crop_x = crop_x_;
        placed.crop_y = crop_y_;
        renderer_.renderWindow(placed, rows, row_stride);
        fillOnHullEdges(edges_, snapped_, values_, window, rows, row_stride);
    }

    void renderWindow(const RenderWindow& window, float* rows, size_t row_stride) const override {
        const uint32_t c = values_.channels;
        if (row_stride == 0) row_stride = size_t(window.width()) * c;
        renderHull(window, rows, row_stride);
        for (size_t i = 0; i < filled_at_.size(); ++i) {
            const auto [x, y] = filled_at_[i];
            if (x < window.x_begin || x >= window.x_end || y < window.y_begin || y >= window.y_end) continue;
            std::memcpy(rows + (y - window.y_begin) * row_stride + size_t(x - window.x_begin) * c,
                        filled_.data() + i * c, c * sizeof(float));
        }
    }

    size_t bytes() const override {
        return values_.pixels.capacity() * sizeof(float) + renderer_.bytes() + edges_.capacity() * sizeof(HullEdge) +
               filled_at_.capacity() * sizeof(filled_at_[0]) + filled_.capacity() * sizeof(float);
    }

    // Whether the output sample at (x, y), in raster.h's units, lies in the hull (snapped as the
    // renderer snaps it for a mesh of points).
    bool covers(int64_t x, int64_t y, OutputSize out) const {
        return snapped_ ? hullContains(edges_, snappedSample(x, out.width), snappedSample(y, out.height))
                        : hullContains(edges_, x, y);
    }
    // Fills the output pixels of `tile_output` outside the hull from the nearest pixel the
    // crop's output has inside it, and keeps them for renderWindow.
    void fillOutside(const RenderWindow& crop_output, const PixelRect& tile_output) {
        const uint32_t c = values_.channels;
        std::vector<float> pixels(size_t(crop_output.width()) * crop_output.height() * c);
        renderHull(crop_output, pixels.data(), size_t(crop_output.width()) * c);
        auto at = [&](uint32_t x, uint32_t y) {
            return pixels.data() + (size_t(y - crop_output.y_begin) * crop_output.width() + (x - crop_output.x_begin)) * c;
        };
        for (uint32_t y = tile_output.y0; y < tile_output.y1; ++y)
            for (uint32_t x = tile_output.x0; x < tile_output.x1; ++x)
                if (std::isnan(*at(x, y))) filled_at_.push_back({x, y});
        fillFromNearest(pixels.data(), crop_output.width(), crop_output.height(), c);
        filled_.resize(filled_at_.size() * c);
        for (size_t i = 0; i < filled_at_.size(); ++i)
            std::memcpy(filled_.data() + i * c, at(filled_at_[i].first, filled_at_[i].second), c * sizeof(float));
    }

private:
    Image values_;
    MeshRenderer renderer_;
    std::vector<HullEdge> edges_;
    bool snapped_;                                          // the mesh has explicit positions
    uint32_t crop_x_, crop_y_;                              // the mesh's crop's corner
    std::vector<std::pair<uint32_t, uint32_t>> filled_at_;  // output pixels outside the hull
    std::vector<float> filled_;                             // their values, channels each
};

}  // namespace

SampledTile shapeSampledTile(Backend& backend, const PackedImage& input, const KnownSamples& known, const Tile& tile,
                             const RenderWindow& frame, uint32_t overlap) {
    // The triangles the tile's output and its flips read lie near its core grown by the
    // overlap: the rect its crop was grown from (KnownSamples::cropFor).
    const uint32_t w = frame.input_width, h = frame.input_height;
    const PixelRect reach{tile.core.x0 - std::min(tile.core.x0, overlap), tile.core.y0 - std::min(tile.core.y0, overlap),
                          std::min(w, tile.core.x1 + overlap), std::min(h, tile.core.y1 + overlap)};
    // The crop's samples, those along the frame's border beyond it, and any others that its
    // triangulation near `reach` turns out to need, until none is missing.
    std::vector<uint32_t> extra = known.samplesAlongBorder(tile.crop);
    SampleSet samples;
    Mesh initial;
    PixelRect bounds;
    for (;;) {
        samples = known.samplesIn(input, tile.crop, extra);
        bounds = known.boundsOf(tile.crop, extra);
        initial = triangulateMerged(samples, {bounds.width(), bounds.height()}, backend);
        const std::vector<uint32_t> missing = known.samplesBreaking(initial, tile.crop, extra, reach);
        if (missing.empty()) break;
        const size_t old_end = extra.size();
        extra.insert(extra.end(), missing.begin(), missing.end());
        std::inplace_merge(extra.begin(), extra.begin() + ptrdiff_t(old_end), extra.end());
    }
    backend.prepareFrom(samples.values, std::move(initial));
    SampledTile shaped;
    shaped.stats = backend.optimize();
    const Mesh mesh = backend.takeMesh();
    RenderWindow placed = frame;
    placed.crop_x = bounds.x0;
    placed.crop_y = bounds.y0;
    auto surface = std::make_unique<SampledSurface>(std::move(samples.values), mesh, placed);
    // The hull is convex: if it holds the corners of the tile's samples, it holds them all.
    const uint32_t in_w = frame.input_width, in_h = frame.input_height, out_w = frame.out.width, out_h = frame.out.height;
    const int64_t left = sampleCoord(tile.output.x0, in_w, out_w), right = sampleCoord(tile.output.x1 - 1, in_w, out_w);
    const int64_t top = sampleCoord(tile.output.y0, in_h, out_h), bottom = sampleCoord(tile.output.y1 - 1, in_h, out_h);
    const OutputSize out = frame.out;
    if (!(surface->covers(left, top, out) && surface->covers(right, top, out) && surface->covers(left, bottom, out) &&
          surface->covers(right, bottom, out))) {
        placed.x_begin = firstOutputOf(tile.crop.x0, in_w, out_w);
        placed.x_end = firstOutputOf(tile.crop.x1, in_w, out_w);
        placed.y_begin = firstOutputOf(tile.crop.y0, in_h, out_h);
        placed.y_end = firstOutputOf(tile.crop.y1, in_h, out_h);
        surface->fillOutside(placed, tile.output);
    }
    shaped.surface = std::move(surface);
    return shaped;
}

}  // namespace ddt
