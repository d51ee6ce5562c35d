// Rendering the optimised piecewise-linear surface at the output size.
//
// Output size: round(s·w) × round(s·h), or a given width or height with the other side
// keeping the aspect. With the realised factors sx = W/w, sy = H/h, output pixel (X, Y)
// samples the mesh at ((X + 0.5)/sx − 0.5, (Y + 0.5)/sy − 0.5), clamped into the hull.
// Triangles are rasterised with exact integer coverage tests (glsl/raster.h), so every
// output pixel is written exactly once and -s 1 reproduces the input exactly.
//
// Tiles: a mesh may be built on a crop of the whole input at an integer offset. Its vertices
// (explicit positions too, which are the crop's) are then placed at their whole-input coordinates, so its output pixels are sampled exactly
// as the whole image's are (same integers, same ties, same weights): where two meshes agree,
// so do their pixels, bit for bit.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "divide_by.h"
#include "image.h"
#include "mesh.h"

namespace ddt {

struct OutputSize {
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t depth = 0;  // a volume's slices (app/volume/); 0 for an image
};

OutputSize scaledOutputSize(uint32_t width, uint32_t height, double scale);
OutputSize outputSizeForWidth(uint32_t width, uint32_t height, uint32_t out_width);
OutputSize outputSizeForHeight(uint32_t width, uint32_t height, uint32_t out_height);

// "" if a width × height input can be rendered at `out`, else the reason (only
// magnification, and sizes whose exact coverage arithmetic fits in 64 bits).
std::string checkOutputSize(uint32_t width, uint32_t height, OutputSize out);

// A rectangle of output pixels, [x_begin, x_end) × [y_begin, y_end) of the whole output
// `out`, rendered from a mesh of the crop at (crop_x, crop_y) of the whole
// input_width × input_height input. The crop must contain every vertex of the triangles
// that cover the rectangle's samples (a tile's crop does: see core/image/tiling.h).
struct RenderWindow {
    uint32_t input_width = 0, input_height = 0;
    OutputSize out;
    uint32_t crop_x = 0, crop_y = 0;
    uint32_t x_begin = 0, x_end = 0, y_begin = 0, y_end = 0;

    uint32_t width() const { return x_end - x_begin; }
    uint32_t height() const { return y_end - y_begin; }
};

// Sample coordinate s (raster.h's units, 1/(2·out_size)) in 1/kPositionOne pixels, rounded: where
// a mesh with explicit positions samples (render.cpp).
int64_t snappedSample(int64_t s, uint32_t out_size);

// Output rows [y_begin, y_end) of an untiled width × height input.
RenderWindow wholeRows(uint32_t width, uint32_t height, OutputSize out, uint32_t y_begin, uint32_t y_end);

// A sample of an untiled output in its triangle: its row-major index and its barycentric
// weights for the triangle's v0, v1, v2.
struct SampleHit {
    uint32_t sample;
    float weights[3];
};

// The surface rendered on the mesh: on each triangle, the linear interpolation of its vertex
// values (plain DDT). With edge bubbles (core/image/reconstruct.h) it becomes quadratic: each edge
// (p, q) adds 4·λp·λq·bubble, which is zero at the vertices and on the other edges, so the
// surface stays continuous and still passes through the vertex values. A quadratic sample is
// clamped to the range of its triangle's vertex values (bounded overshoot), and premultiplied
// colour to at most its alpha.
class MeshRenderer {
public:
    // `image` holds the vertex values (premultiplied), pixel v for vertex v: the image the
    // mesh's grid was made of, or for a mesh of points one value per point (an n × 1 image);
    // `bubbles`, if not null, edgeCount() × channels values. All must outlive the renderer.
    MeshRenderer(const Mesh& mesh, const Image& image, const float* bubbles = nullptr);
    // A renderer of the same mesh as `tables` for another surface, taking over its triangle
    // tables instead of building them again.
    MeshRenderer(MeshRenderer&& tables, const Image& image, const float* bubbles = nullptr);

    // Renders the window into `rows`: window.width() × channels floats per row, or
    // `row_stride` floats from one row's start to the next (a window of a wider band).
    void renderWindow(const RenderWindow& window, float* rows, size_t row_stride = 0) const;
    // Output rows [y_begin, y_end) of the whole image (`image` is the whole input).
    void renderRows(OutputSize out, uint32_t y_begin, uint32_t y_end, float* rows) const;

    // The samples of an untiled output of size `out` (below 2^32 samples) that lie in
    // triangles [first, end) of triangles(), appended to `hits` triangle by triangle, each
    // triangle's in row-major order; ends[t − first] = hits.size() after triangle t's.
    void locateSamples(OutputSize out, uint32_t first, uint32_t end, std::vector<SampleHit>& hits, uint32_t* ends) const;
    const std::vector<Triangle>& triangles() const { return triangles_; }
    // The bytes of its tables (not of the values and bubbles it reads).
    size_t bytes() const {
        return positions_.capacity() * sizeof(Position) + triangles_.capacity() * sizeof(Triangle) +
               first_in_row_.capacity() * sizeof(uint32_t);
    }

private:
    std::pair<uint32_t, uint32_t> trianglesAround(const RenderWindow& window) const;
    // The first and last crop row a triangle's vertices touch (rounded outwards).
    std::pair<uint32_t, uint32_t> rowsOf(const Triangle& t) const;
    template <typename Visit>
    void visitSamples(const RenderWindow& window, uint32_t first, uint32_t end, Visit visit) const;

    const Image& image_;
    const float* bubbles_;
    uint32_t width_ = 0, height_ = 0;        // the mesh's frame (its crop of the input)
    DivideBy by_width_;                      // a grid vertex's row (a grid is at least 2 wide)
    std::vector<Position> positions_;        // the mesh's explicit positions (empty: the grid's)
    std::vector<Triangle> triangles_;        // sorted by their top row
    std::vector<uint32_t> first_in_row_;     // index of the first triangle per top row, + end
    uint32_t tallest_ = 0;                   // most rows any triangle spans
};

// Renders `window` with `renderer` in bands of rows on the threads of core/parallel.h: each
// band writes only its own rows, so the result does not depend on the split. `finish`, if
// set, then works on each band's rows on the same thread (the convolution fallback's blend).
using BandFinish = std::function<void(const RenderWindow& band, float* band_rows)>;
void renderInParallel(const MeshRenderer& renderer, const RenderWindow& window, uint32_t channels, float* rows,
                      const BandFinish& finish = {});

// Output rows per band of renderInParallel: enough to amortise finding a band's triangles
// (those that start up to the tallest triangle's height above it) and scanning a triangle
// twice where a band's edge cuts it. 64 rather than 16: 3 % less processor time on the ×4
// photograph of bench/e2e's job b, the same bytes.
constexpr uint32_t kRowsPerRenderBand = 64;

// Renders the whole image in memory (tests, bench); `bubbles` as for MeshRenderer.
Image renderImage(const Mesh& mesh, const Image& image, OutputSize out, const float* bubbles = nullptr);

}  // namespace ddt
