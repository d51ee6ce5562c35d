#include "greedy_simplify.h"

#include <algorithm>
#include <cmath>
#include <queue>

#include "edge_collapse.h"
#include "quadric.h"
#include "reconstruct.h"

namespace ddt {

namespace {

// A vertex as a point of the quadrics' space: position, then its pixel's channels.
struct Points {
    const Image& image;
    uint32_t n;

    void of(uint32_t v, double* point) const {
        point[0] = kPositionWeight * double(v % image.width);
        point[1] = kPositionWeight * double(v / image.width);
        for (uint32_t k = 0; k < image.channels; ++k) point[2 + k] = image.pixels[size_t(v) * image.channels + k];
    }
};

std::vector<Quadric> vertexQuadrics(const Mesh& mesh, const Points& points) {
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

// Each kept vertex's colour: its quadric's minimum where it stands.
void setBestColours(const Mesh& mesh, const std::vector<Quadric>& quadrics, const Points& points, Image& image) {
    std::vector<bool> used(mesh.vertexCount(), false);
    for (const EdgeVertices& v : mesh.vertices) used[v.a] = used[v.b] = true;
    const uint32_t c = image.channels;
    const bool bounded = boundedToUnit(image.sample_type);
    std::vector<float> best(image.pixels);
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        if (!used[v]) continue;
        double point[kMaxQuadricDimensions];
        points.of(v, point);
        if (!quadrics[v].minimiseTail(point, 2, points.n)) continue;
        float* colour = &best[size_t(v) * c];
        for (uint32_t k = 0; k < c; ++k) colour[k] = bounded ? float(std::clamp(point[2 + k], 0.0, 1.0)) : float(point[2 + k]);
        if (image.hasAlpha())
            for (uint32_t k = 0; k + 1 < c; ++k) colour[k] = std::min(colour[k], colour[c - 1]);
    }
    image.pixels = std::move(best);
}

struct Candidate {
    double cost;
    uint32_t edge;
    bool b_into_a;
    uint32_t version;

    // The queue's top is the least cost, then the lowest edge id, then b into a.
    bool operator<(const Candidate& other) const {
        if (cost != other.cost) return cost > other.cost;
        if (edge != other.edge) return edge > other.edge;
        return b_into_a < other.b_into_a;
    }
};

}  // namespace

uint32_t usedVertexCount(const Mesh& mesh) {
    std::vector<bool> used(mesh.vertexCount(), false);
    for (const EdgeVertices& v : mesh.vertices)
        if (v.a != kNone) used[v.a] = used[v.b] = true;
    return uint32_t(std::count(used.begin(), used.end(), true));
}

SimplifyStats simplifySerial(Mesh& mesh, Image& image, uint32_t target) {
    SimplifyStats stats;
    stats.vertices_before = stats.vertices_after = usedVertexCount(mesh);
    const Points points{image, 2 + image.channels};
    std::vector<Quadric> quadrics = vertexQuadrics(mesh, points);
    VertexEdges edges(mesh);
    std::vector<uint32_t> version(mesh.edgeCount(), 0);
    std::vector<bool> blocked(mesh.edgeCount(), false);  // its best candidate was illegal when it came up
    std::priority_queue<Candidate> queue;

    auto push = [&](uint32_t e) {
        const uint32_t a = mesh.vertices[e].a, b = mesh.vertices[e].b;
        Quadric sum = quadrics[a];
        sum += quadrics[b];
        double pa[kMaxQuadricDimensions], pb[kMaxQuadricDimensions];
        points.of(a, pa);
        points.of(b, pb);
        ++version[e];
        blocked[e] = false;
        queue.push({sum.at(pa, points.n), e, true, version[e]});
        queue.push({sum.at(pb, points.n), e, false, version[e]});
    };
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) push(e);

    while (stats.vertices_after > target && !queue.empty()) {
        const Candidate next = queue.top();
        queue.pop();
        if (next.version != version[next.edge] || removedEdge(mesh, next.edge)) continue;  // stale
        const Collapse collapse{next.edge, next.b_into_a};
        // An illegal collapse waits until a change around it pushes its edge again. (Its other
        // direction is still queued, unless it came up first.)
        if (!canCollapse(mesh, edges, collapse)) {
            blocked[next.edge] = true;
            continue;
        }
        const uint32_t from = collapse.from(mesh), to = collapse.to(mesh);
        collapseEdge(mesh, edges, collapse);
        quadrics[to] += quadrics[from];
        ++stats.collapses;
        --stats.vertices_after;
        stats.last_cost = next.cost;
        // The edges at `to` have new costs; blocked ones at its neighbours may have become legal
        // (legality depends on the triangles around an edge's vertices, which changed there).
        for (uint32_t f : edges.at[to]) push(f);
        for (uint32_t f : edges.at[to]) {
            const uint32_t x = mesh.vertices[f].a == to ? mesh.vertices[f].b : mesh.vertices[f].a;
            for (uint32_t g : edges.at[x])
                if (blocked[g]) push(g);
        }
    }
    compactEdges(mesh);
    setBestColours(mesh, quadrics, points, image);
    return stats;
}

}  // namespace ddt
