// What the serial and the parallel simplifier share: vertices as points of the quadrics'
// space (quadric.h), each vertex's starting quadric, and the kept vertices' colours at the end
// (the collapses' places and costs: placement.h).
#pragma once

#include <cstdint>
#include <vector>

#include "colour_fit.h"
#include "edge_collapse.h"
#include "image.h"
#include "mesh.h"
#include "quadric.h"

namespace ddt {

// A vertex as a point: its position (in pixels) times kPositionWeight, then its pixel's
// channels.
struct QuadricPoints {
    const Mesh& mesh;  // whose positions the simplifier moves
    const Image& image;
    uint32_t n;  // 2 + channels

    void of(uint32_t v, double* point) const {
        at(positionOf(mesh, v), point);
        for (uint32_t k = 0; k < image.channels; ++k) point[2 + k] = image.pixels[size_t(v) * image.channels + k];
    }
    // Sets the point's position coordinates to `p`'s.
    static void at(Position p, double* point) {
        point[0] = kPositionWeight * double(p.x) / kPositionOne;
        point[1] = kPositionWeight * double(p.y) / kPositionOne;
    }
    // The bits of minimiseFree's `free` for the colour axes, and for all axes.
    uint32_t colourAxes() const { return ((1u << n) - 1) & ~3u; }
    uint32_t allAxes() const { return (1u << n) - 1; }
};

// Each vertex's quadric: the planes of its triangles, weighted by their areas.
std::vector<Quadric> vertexQuadrics(const Mesh& mesh, const QuadricPoints& points);

// exceedsErrorLimit's limit for an error of `max_error` 8-bit levels (0: none).
inline double errorLimitOf(double max_error) { return max_error > 0.0 ? (max_error / 255.0) * (max_error / 255.0) : 0.0; }

// What both simplifiers start from: the points, each vertex's quadric, each vertex's edges
// and, for a triangulation of samples, the samples the colours are fitted to (colour_fit.h).
struct SimplifyStart {
    QuadricPoints points;
    std::vector<Quadric> quadrics;
    VertexEdges edges;
    std::vector<KnownSample> samples;

    SimplifyStart(const Mesh& mesh, const Image& values)
        : points{mesh, values, 2 + values.channels},
          quadrics(vertexQuadrics(mesh, points)),
          edges(mesh),
          samples(mesh.hull == MeshHull::convex ? knownSamplesOf(mesh) : std::vector<KnownSample>{}) {}
};

// Which vertex ids the mesh's edges use.
std::vector<bool> usedVertices(const Mesh& mesh);

// Each kept vertex's colour: its quadric's minimum where it stands, then all of them fitted
// together to the picture's pixels (colour_fit.h), within [0, 1] for integer sample types and,
// premultiplied, within its alpha. `image` holds the picture on entry. A vertex on a locked
// side keeps its pixel's colour, which the neighbouring tile's mesh gives it too.
void setVertexColours(const Mesh& mesh, const SimplifyStart& start, Image& image);

}  // namespace ddt
