// Rendering a triangulation of samples (core/delaunay/delaunay.h): inside the hull of its
// vertices, the plain DDT surface of core/image/render.h (exact coverage, each output pixel once);
// outside it, where the grid's mesh would still reach (the hull need not be the image's
// rectangle), the value of the nearest rendered pixel (core/delaunay/nearest_fill.h).
#pragma once

#include "image.h"
#include "mesh.h"
#include "render.h"

namespace ddt {

// The whole output in memory: `values` holds the vertex values (premultiplied), by vertex id,
// as for MeshRenderer; the mesh's hull must contain at least one output sample.
Image renderSampledMesh(const Mesh& mesh, const Image& values, OutputSize out);

}  // namespace ddt
