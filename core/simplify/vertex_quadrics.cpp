#include "vertex_quadrics.h"

#include <algorithm>
#include <cmath>

#include "colour_fit.h"
#include "reconstruct.h"

namespace ddt {

std::vector<Quadric> vertexQuadrics(const Mesh& mesh, const QuadricPoints& points) {
    std::vector<Quadric> quadrics(mesh.vertexCount());
    forEachTriangle(mesh, [&](const Triangle& t) {
        double p[kMaxQuadricDimensions], q[kMaxQuadricDimensions], r[kMaxQuadricDimensions];
        points.of(t.v0, p);
        points.of(t.v1, q);
        points.of(t.v2, r);
        const double area = 0.5 * std::abs((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])) /
                            (kPositionWeight * kPositionWeight);
        const Quadric plane = planeQuadric(p, q, r, points.n, area);
        for (uint32_t v : {t.v0, t.v1, t.v2}) quadrics[v] += plane;
    });
    return quadrics;
}

std::vector<bool> usedVertices(const Mesh& mesh) {
    std::vector<bool> used(mesh.vertexCount(), false);
    for (const EdgeVertices& v : mesh.vertices)
        if (v.a != kNone) used[v.a] = used[v.b] = true;
    return used;
}

void setVertexColours(const Mesh& mesh, const SimplifyStart& start, Image& image) {
    const auto& [points, quadrics, edges, samples] = start;
    const std::vector<bool> used = usedVertices(mesh);
    const uint32_t c = image.channels;
    const bool bounded = boundedToUnit(image.sample_type);
    std::vector<float> best(image.pixels);
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        if (!used[v] || lockedVertex(mesh, v)) continue;
        double point[kMaxQuadricDimensions];
        points.of(v, point);
        if (!quadrics[v].minimiseFree(point, points.colourAxes(), points.n)) continue;
        float* colour = &best[size_t(v) * c];
        for (uint32_t k = 0; k < c; ++k) colour[k] = bounded ? float(std::clamp(point[2 + k], 0.0, 1.0)) : float(point[2 + k]);
        if (image.hasAlpha())
            for (uint32_t k = 0; k + 1 < c; ++k) colour[k] = std::min(colour[k], colour[c - 1]);
    }
    Image colours = image;
    colours.pixels = std::move(best);
    fitColours(mesh, image, colours, samples);
    image.pixels = std::move(colours.pixels);
}

}  // namespace ddt
