// Rendering the optimised piecewise-linear surface at the output size.
//
// Output size: round(s·w) × round(s·h), or a given width or height with the other side
// keeping the aspect. With the realised factors sx = W/w, sy = H/h, output pixel (X, Y)
// samples the mesh at ((X + 0.5)/sx − 0.5, (Y + 0.5)/sy − 0.5), clamped into the hull.
// Triangles are rasterised with exact integer coverage tests (glsl/raster.h), so every
// output pixel is written exactly once and -s 1 reproduces the input exactly.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image.h"
#include "mesh.h"

namespace ddt {

struct OutputSize {
    uint32_t width = 0;
    uint32_t height = 0;
};

OutputSize scaledOutputSize(uint32_t width, uint32_t height, double scale);
OutputSize outputSizeForWidth(uint32_t width, uint32_t height, uint32_t out_width);
OutputSize outputSizeForHeight(uint32_t width, uint32_t height, uint32_t out_height);

// "" if a width × height input can be rendered at `out`, else the reason (only
// magnification, and sizes whose exact coverage arithmetic fits in 64 bits).
std::string checkOutputSize(uint32_t width, uint32_t height, OutputSize out);

class MeshRenderer {
public:
    // `image` holds the vertex values (premultiplied); both must outlive the renderer.
    MeshRenderer(const Mesh& mesh, const Image& image, OutputSize out);

    // Renders output rows [y_begin, y_end) into `rows`: out.width × channels floats per row.
    void renderRows(uint32_t y_begin, uint32_t y_end, float* rows) const;

private:
    const Image& image_;
    OutputSize out_;
    std::vector<Triangle> triangles_;        // sorted by their top row
    std::vector<uint32_t> first_in_row_;     // index of the first triangle per top row, + end
    uint32_t tallest_ = 0;                   // most rows any triangle spans
};

// Renders the whole image in memory (tests, bench).
Image renderImage(const Mesh& mesh, const Image& image, OutputSize out);

}  // namespace ddt
