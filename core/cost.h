// Sederberg's cost of a triangulation over an image (paper Sec. 2.1).
//
// The cost is computed on luminance Y = 0.299 R + 0.587 G + 0.114 B of the stored values in
// [0, 1] (grey images: the grey value). For images with alpha, Y is taken from the
// premultiplied colour (what gets interpolated) and the SCF of the alpha channel is added,
// so alpha edges are optimised too. Boundary edges cost 0; the mesh cost is the sum over
// edges. The formulas themselves live in glsl/sederberg.h, shared with the kernels.
#pragma once

#include <cstdint>
#include <vector>

#include "image.h"
#include "mesh.h"

namespace ddt {

// Per-vertex values the cost looks at.
struct CostField {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> luma;
    std::vector<float> alpha;  // empty for images without alpha
};

CostField costFieldOf(const Image& image);

// Cost of edge e (0 for a boundary edge).
double edgeCost(const Mesh& mesh, const CostField& field, uint32_t e);

// Sum of edgeCost over all edges, in id order.
double meshCost(const Mesh& mesh, const CostField& field);

// Cost decrease if e were flipped, or -infinity when its quadrilateral is not strictly
// convex (boundary edges included): such an edge is locally optimal by definition.
double flipGainOf(const Mesh& mesh, const CostField& field, uint32_t e);

}  // namespace ddt
