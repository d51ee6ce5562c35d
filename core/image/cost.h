// The cost of a triangulation over an image: Sederberg's (paper Sec. 2.1, the default) or one
// of Tóth et al.'s content-weighted costs (variance, face-SCF; glsl/image/content_cost.h).
//
// The cost is computed on luminance Y = 0.299 R + 0.587 G + 0.114 B of the stored values in
// [0, 1] (grey images: the grey value). For images with alpha, Y is taken from the
// premultiplied colour (what gets interpolated) and the cost of the alpha channel is added,
// so alpha edges are optimised too. Boundary edges have no SCF. Every cost is a sum over edges
// of a share (edgeCost): Sederberg's the SCF; face-SCF's the SCF · (area_l + area_r) / 3 (a
// triangle's weight is the mean of its edges' SCF); variance's the area · variance of the
// triangles whose lowest-id edge is e (so each triangle counts once, in forEachTriangle's
// order). The formulas themselves live in glsl/image/sederberg.h and glsl/image/content_cost.h, shared
// with the kernels.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "content_cost.h"
#include "image.h"
#include "mesh.h"

namespace ddt {

// The cost the optimizer lowers (LawsonOptions::cost, VulkanOptions::cost).
enum class CostFunction : uint32_t {
    sederberg = kCostSederberg,  // Σ over edges of SCF
    variance = kCostVariance,    // Σ over triangles of area × variance of the 3 vertex values
    face_scf = kCostFaceScf,     // Σ over triangles of area × mean SCF over its 3 edges
};

// "sederberg", "variance", "face-scf" (the command line's spelling).
const char* costFunctionName(CostFunction cost);
// The cost of a name costFunctionName gives, or nothing.
std::optional<CostFunction> parseCostFunction(const std::string& name);

// Per-vertex values the cost looks at, indexed by vertex id: luma[v] is vertex v's. width and
// height are the image's, not the mesh's: the vertices' places come from the mesh (placesOf;
// for a mesh with explicit positions, costFieldOf of an image whose pixel v is vertex v's value).
struct CostField {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> luma;
    std::vector<float> alpha;  // empty for images without alpha
};

CostField costFieldOf(const Image& image);

// Edge e's share of the mesh cost (see the top; Sederberg's and face-SCF's are 0 for a
// boundary edge).
double edgeCost(const Mesh& mesh, const CostField& field, uint32_t e, CostFunction cost = CostFunction::sederberg);

// Sum of edgeCost over all edges, in id order.
double meshCost(const Mesh& mesh, const CostField& field, CostFunction cost = CostFunction::sederberg);

// Cost decrease if e were flipped, or -infinity when its quadrilateral is not strictly
// convex (boundary edges included): such an edge is locally optimal by definition.
double flipGainOf(const Mesh& mesh, const CostField& field, uint32_t e, CostFunction cost = CostFunction::sederberg);

// The edges whose flip can change e's gain under `cost` (its ROI, core/image/mesh.h): 1 for variance
// (the gain reads e's record only), 2 for Sederberg and face-SCF (e's and its neighbours').
int roiDegree(CostFunction cost);

}  // namespace ddt
