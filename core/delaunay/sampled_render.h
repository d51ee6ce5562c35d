// Rendering a triangulation of samples (core/delaunay/delaunay.h): inside the hull of its
// vertices, the plain DDT surface of core/image/render.h (exact coverage, each output pixel once);
// outside it, where the grid's mesh would still reach (the hull need not be the image's
// rectangle), the value of the nearest rendered pixel (core/delaunay/nearest_fill.h).
#pragma once

#include <vector>

#include "image.h"
#include "mesh.h"
#include "render.h"

namespace ddt {

// The whole output in memory: `values` holds the vertex values (premultiplied), by vertex id,
// as for MeshRenderer; the mesh's hull must contain at least one output sample.
Image renderSampledMesh(const Mesh& mesh, const Image& values, OutputSize out);

// A boundary edge of the mesh (on its hull): its vertices, their places in the renderer's units
// (raster.h's for a grid's vertices, explicit positions in theirs, both shifted by the crop's
// offset) and the side its one triangle is on.
struct HullEdge {
    uint32_t a, b;
    int64_t px, py, qx, qy;
    bool inside_left;  // the triangle lies left of a→b
};
// The hull edges of `mesh`, placed for windows of the output `frame` (its crop_x, crop_y, out).
std::vector<HullEdge> hullEdgesOf(const Mesh& mesh, const RenderWindow& frame);

// A sample lying exactly on a hull edge belongs to the edge's triangle only when the raster
// tie-break (raster.h: a push right, then down) moves it inwards; one pushed out of the hull is
// left NaN by the renderer and gets the edge's linear value here, so that the hull keeps its
// exact values (a known pixel at ×1 among them) rather than a neighbour's. Only NaN samples of
// `window` change; `rows` as for MeshRenderer::renderWindow; `snapped`: the mesh has positions.
void fillOnHullEdges(const std::vector<HullEdge>& edges, bool snapped, const Image& values, const RenderWindow& window,
                     float* rows, size_t row_stride = 0);

// Whether the point (x, y), in the edges' units, lies inside the hull or on it.
bool hullContains(const std::vector<HullEdge>& edges, int64_t x, int64_t y);

}  // namespace ddt
