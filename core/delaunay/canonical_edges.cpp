#include "canonical_edges.h"

#include <algorithm>

namespace ddt {

// Counting sort by the smaller end, then each vertex's few edges sorted by the larger end.
void renumberCanonically(Mesh& mesh) {
    const uint32_t edges = mesh.edgeCount(), vertices = mesh.vertexCount();
    // End for end: (a, b, l, r) → (b, a, r, l), and so (bl, la, ar, rb) → (ar, rb, bl, la).
    for (uint32_t e = 0; e < edges; ++e) {
        EdgeVertices& v = mesh.vertices[e];
        if (v.a < v.b) continue;
        EdgeNeighbours& n = mesh.neighbours[e];
        v = {v.b, v.a, v.r, v.l};
        n = {n.ar, n.rb, n.bl, n.la};
    }
    std::vector<uint32_t> first(size_t(vertices) + 1, 0);
    for (const EdgeVertices& v : mesh.vertices) ++first[v.a + 1];
    for (uint32_t u = 0; u < vertices; ++u) first[u + 1] += first[u];
    std::vector<uint32_t> order(edges);  // new id → old id
    {
        std::vector<uint32_t> fill(first.begin(), first.end() - 1);
        for (uint32_t e = 0; e < edges; ++e) order[fill[mesh.vertices[e].a]++] = e;
    }
    for (uint32_t u = 0; u < vertices; ++u)
        std::sort(order.begin() + first[u], order.begin() + first[u + 1],
                  [&](uint32_t e, uint32_t f) { return mesh.vertices[e].b < mesh.vertices[f].b; });
    std::vector<uint32_t> new_id(edges);
    for (uint32_t e = 0; e < edges; ++e) new_id[order[e]] = e;
    auto renamed = [&](uint32_t e) { return e == kNone ? kNone : new_id[e]; };
    std::vector<EdgeVertices> vertex_records(edges);
    std::vector<EdgeNeighbours> neighbour_records(edges);
    for (uint32_t e = 0; e < edges; ++e) {
        vertex_records[e] = mesh.vertices[order[e]];
        const EdgeNeighbours& n = mesh.neighbours[order[e]];
        neighbour_records[e] = {renamed(n.bl), renamed(n.la), renamed(n.ar), renamed(n.rb)};
    }
    mesh.vertices = std::move(vertex_records);
    mesh.neighbours = std::move(neighbour_records);
}

}  // namespace ddt
