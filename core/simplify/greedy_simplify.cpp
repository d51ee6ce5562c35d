#include "greedy_simplify.h"

#include <algorithm>
#include <queue>

#include "edge_collapse.h"
#include "placement.h"
#include "vertex_quadrics.h"

namespace ddt {

namespace {

struct Candidate {
    double cost;
    Collapse collapse;
    uint32_t version;

    // The queue's top is the least cost, then the lowest edge id, then b into a.
    bool operator<(const Candidate& other) const {
        if (cost != other.cost) return cost > other.cost;
        if (collapse.edge != other.collapse.edge) return collapse.edge > other.collapse.edge;
        return collapse.b_into_a < other.collapse.b_into_a;
    }
};

}  // namespace

uint32_t usedVertexCount(const Mesh& mesh) {
    const std::vector<bool> used = usedVertices(mesh);
    return uint32_t(std::count(used.begin(), used.end(), true));
}

SimplifyStats simplifySerial(Mesh& mesh, Image& image, uint32_t target, double max_error) {
    SimplifyStats stats;
    stats.vertices_before = stats.vertices_after = usedVertexCount(mesh);
    if (stats.vertices_after <= target) return stats;  // nothing to do: the picture is the mesh's colours
    makePositionsExplicit(mesh);
    SimplifyStart start(mesh, image);
    const double error_limit = errorLimitOf(max_error);
    auto& [points, quadrics, edges, samples] = start;
    std::vector<uint32_t> version(mesh.edgeCount(), 0);
    std::vector<bool> blocked(mesh.edgeCount(), false);  // its best candidate was illegal when it came up
    std::priority_queue<Candidate> queue;

    auto push = [&](uint32_t e) {
        ++version[e];
        blocked[e] = false;
        Quadric merged = quadrics[mesh.vertices[e].a];
        merged += quadrics[mesh.vertices[e].b];
        for (const PlacedCollapse& placed : placeCollapses(mesh, edges, points, merged, e))
            queue.push({placed.cost, placed.collapse, version[e]});
    };
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) push(e);

    while (stats.vertices_after > target && !queue.empty()) {
        const Candidate next = queue.top();
        queue.pop();
        if (next.version != version[next.collapse.edge] || removedEdge(mesh, next.collapse.edge)) continue;  // stale
        const Collapse collapse = next.collapse;
        // An illegal collapse waits until a change around it pushes its edge again. (Its other
        // direction is still queued, unless it came up first.)
        if (!canCollapse(mesh, edges, collapse)) {
            blocked[collapse.edge] = true;
            continue;
        }
        const uint32_t from = collapse.from(mesh), to = collapse.to(mesh);
        // Too costly: skipped, until a collapse nearby changes its cost and queues it again.
        if (exceedsErrorLimit(next.cost, quadrics[from].area + quadrics[to].area, error_limit)) continue;
        collapseEdge(mesh, edges, collapse);
        quadrics[to] += quadrics[from];
        ++stats.collapses;
        --stats.vertices_after;
        stats.last_cost = next.cost;
        // The edges at `to` have new costs; blocked ones at its neighbours may have become legal
        // (legality depends on the triangles around an edge's vertices, which changed there).
        forEachEdgeAt(mesh, edges, to, [&](uint32_t f) {
            push(f);
            const uint32_t x = mesh.vertices[f].a == to ? mesh.vertices[f].b : mesh.vertices[f].a;
            forEachEdgeAt(mesh, edges, x, [&](uint32_t g) {
                if (blocked[g]) push(g);
            });
        });
    }
    compactEdges(mesh);
    setVertexColours(mesh, start, image);
    return stats;
}

}  // namespace ddt
