// What the serial and the parallel simplifier share: vertices as points of the quadrics'
// space (quadric.h), each vertex's starting quadric, the collapse costs, and the kept
// vertices' best colours at the end.
#pragma once

#include <cstdint>
#include <vector>

#include "edge_collapse.h"
#include "image.h"
#include "mesh.h"
#include "quadric.h"

namespace ddt {

// A vertex as a point: its position times kPositionWeight, then its pixel's channels.
struct QuadricPoints {
    const Image& image;
    uint32_t n;  // 2 + channels

    void of(uint32_t v, double* point) const {
        point[0] = kPositionWeight * double(v % image.width);
        point[1] = kPositionWeight * double(v / image.width);
        for (uint32_t k = 0; k < image.channels; ++k) point[2 + k] = image.pixels[size_t(v) * image.channels + k];
    }
};

// Each vertex's quadric: the planes of its triangles, weighted by their areas.
std::vector<Quadric> vertexQuadrics(const Mesh& mesh, const QuadricPoints& points);

// The error of a collapse: the merged quadric at the point of the vertex that stays.
double collapseCost(const Mesh& mesh, const std::vector<Quadric>& quadrics, const QuadricPoints& points, Collapse collapse);

// exceedsErrorLimit's limit for an error of `max_error` 8-bit levels (0: none).
inline double errorLimitOf(double max_error) { return max_error > 0.0 ? (max_error / 255.0) * (max_error / 255.0) : 0.0; }

// What both simplifiers start from: the points, each vertex's quadric, each vertex's edges.
struct SimplifyStart {
    QuadricPoints points;
    std::vector<Quadric> quadrics;
    VertexEdges edges;

    SimplifyStart(const Mesh& mesh, const Image& values)
        : points{values, 2 + values.channels}, quadrics(vertexQuadrics(mesh, points)), edges(mesh) {}
};

// Which vertex ids the mesh's edges use.
std::vector<bool> usedVertices(const Mesh& mesh);

// Each kept vertex's colour: its quadric's minimum where it stands, within [0, 1] for integer
// sample types and, premultiplied, within its alpha.
void setBestColours(const Mesh& mesh, const std::vector<Quadric>& quadrics, const QuadricPoints& points, Image& image);

}  // namespace ddt
