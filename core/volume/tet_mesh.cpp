#include "tet_mesh.h"

#include <algorithm>
#include <cassert>
#include <sstream>

namespace ddt {

namespace {

// The six orders of the axes; a cell's tet p walks from the cell's corner (x, y, z) along
// kAxisOrders[p][0], then [1], then [2] to the opposite corner.
constexpr std::array<std::array<int, 3>, 6> kAxisOrders = {
    {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};

uint32_t orderIndex(int a, int b, int c) {
    for (uint32_t p = 0; p < 6; ++p)
        if (kAxisOrders[p][0] == a && kAxisOrders[p][1] == b && kAxisOrders[p][2] == c) return p;
    assert(false);
    return 0;
}

// The walk's tet has orientation det[e_a, e_b, e_c], the order's sign. Odd orders store their
// last two walk vertices swapped, so every tet is positive; kStoredToWalk maps a stored vertex
// index to the walk's.
bool isOddOrder(uint32_t p) { return p == 1 || p == 2 || p == 5; }
int walkIndexOf(uint32_t p, int stored) {
    if (!isOddOrder(p) || stored < 2) return stored;
    return 5 - stored;
}

}  // namespace

int64_t orientOf(const TetMesh& mesh, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    const VertexCoordinates pa = coordinatesOf(mesh, a), pb = coordinatesOf(mesh, b);
    const VertexCoordinates pc = coordinatesOf(mesh, c), pd = coordinatesOf(mesh, d);
    return tetOrient(pa.x, pa.y, pa.z, pb.x, pb.y, pb.z, pc.x, pc.y, pc.z, pd.x, pd.y, pd.z);
}

TetMesh kuhnTetMesh(const std::array<uint32_t, 3>& size) {
    for ([[maybe_unused]] uint32_t n : size) assert(n >= 2 && n <= kMaxTetMeshSide);
    TetMesh mesh;
    mesh.size = size;
    const std::array<uint32_t, 3> cells = {size[0] - 1, size[1] - 1, size[2] - 1};
    const size_t cell_count = size_t(cells[0]) * cells[1] * cells[2];
    mesh.vertices.resize(6 * cell_count);
    mesh.neighbours.resize(6 * cell_count);
    const std::array<uint32_t, 3> vertex_step = {1, size[0], size[0] * size[1]};
    const std::array<int64_t, 3> cell_step = {1, cells[0], int64_t(cells[0]) * cells[1]};

    size_t cell = 0;
    for (uint32_t z = 0; z < cells[2]; ++z)
        for (uint32_t y = 0; y < cells[1]; ++y)
            for (uint32_t x = 0; x < cells[0]; ++x, ++cell) {
                const std::array<uint32_t, 3> corner = {x, y, z};
                for (uint32_t p = 0; p < 6; ++p) {
                    const auto& order = kAxisOrders[p];
                    std::array<uint32_t, 4> walk;
                    walk[0] = x + size[0] * (y + size[1] * z);
                    for (int k = 0; k < 3; ++k) walk[k + 1] = walk[k] + vertex_step[order[k]];
                    const uint32_t t = uint32_t(6 * cell + p);
                    for (int s = 0; s < 4; ++s) mesh.vertices[t][s] = walk[walkIndexOf(p, s)];

                    // The tet across the face opposite walk vertex k (see the Freudenthal
                    // subdivision): k = 0 and 3 lie in the next and previous cell along the
                    // first and last axis, with the order rotated; k = 1 and 2 in this cell,
                    // with two neighbouring axes swapped.
                    std::array<uint32_t, 4> across_walk;  // neighbour slot per walk vertex
                    const int a = order[0], b = order[1], c = order[2];
                    across_walk[0] = corner[a] + 1 < cells[a]
                                         ? uint32_t(6 * (int64_t(cell) + cell_step[a]) + orderIndex(b, c, a))
                                         : kNoTet;
                    across_walk[3] = corner[c] > 0
                                         ? uint32_t(6 * (int64_t(cell) - cell_step[c]) + orderIndex(c, a, b))
                                         : kNoTet;
                    across_walk[1] = uint32_t(6 * cell + orderIndex(b, a, c));
                    across_walk[2] = uint32_t(6 * cell + orderIndex(a, c, b));
                    for (int s = 0; s < 4; ++s) mesh.neighbours[t][s] = across_walk[walkIndexOf(p, s)];
                }
            }
    return mesh;
}

namespace {

struct FaceRecord {
    std::array<uint32_t, 3> vertices;  // sorted
    uint32_t tet;
    uint32_t face;
    bool operator<(const FaceRecord& o) const { return vertices < o.vertices; }
};

bool onOneBoxSide(const TetMesh& mesh, const std::array<uint32_t, 3>& face) {
    const VertexCoordinates p[3] = {coordinatesOf(mesh, face[0]), coordinatesOf(mesh, face[1]),
                                    coordinatesOf(mesh, face[2])};
    const int high[3] = {int(mesh.size[0]) - 1, int(mesh.size[1]) - 1, int(mesh.size[2]) - 1};
    auto all = [&](auto coordinate, int value) {
        return coordinate(p[0]) == value && coordinate(p[1]) == value && coordinate(p[2]) == value;
    };
    const auto x = [](const VertexCoordinates& q) { return q.x; };
    const auto y = [](const VertexCoordinates& q) { return q.y; };
    const auto z = [](const VertexCoordinates& q) { return q.z; };
    return all(x, 0) || all(x, high[0]) || all(y, 0) || all(y, high[1]) || all(z, 0) || all(z, high[2]);
}

std::array<uint32_t, 3> sortedFace(const TetVertices& t, uint32_t face) {
    std::array<uint32_t, 3> f;
    for (uint32_t k = 0, j = 0; k < 4; ++k)
        if (k != face) f[j++] = t[k];
    std::sort(f.begin(), f.end());
    return f;
}

std::string tetProblem(uint32_t t, const TetVertices& v, const std::string& what) {
    std::ostringstream out;
    out << "tet " << t << " (" << v[0] << ", " << v[1] << ", " << v[2] << ", " << v[3] << "): " << what;
    return out.str();
}

}  // namespace

std::string checkTetMesh(const TetMesh& mesh) {
    for (uint32_t n : mesh.size)
        if (n < 2 || n > kMaxTetMeshSide) return "grid side outside [2, 2^16]";
    if (mesh.neighbours.size() != mesh.vertices.size()) return "wrong number of neighbour records";

    std::vector<uint32_t> free_slots = mesh.free_slots;
    std::sort(free_slots.begin(), free_slots.end());
    if (std::adjacent_find(free_slots.begin(), free_slots.end()) != free_slots.end())
        return "a free slot listed twice";
    std::vector<FaceRecord> faces;
    faces.reserve(size_t(mesh.tetCount()) * 4);
    __int128 volume = 0;
    for (uint32_t t = 0; t < mesh.slotCount(); ++t) {
        const TetVertices& v = mesh.vertices[t];
        const bool listed_free = std::binary_search(free_slots.begin(), free_slots.end(), t);
        if (!mesh.inUse(t)) {
            if (!listed_free) return tetProblem(t, v, "unused record not listed as free");
            continue;
        }
        if (listed_free) return tetProblem(t, v, "record in use but listed as free");
        for (uint32_t k = 0; k < 4; ++k) {
            if (v[k] >= mesh.vertexCount()) return tetProblem(t, v, "vertex id out of range");
            for (uint32_t j = 0; j < k; ++j)
                if (v[j] == v[k]) return tetProblem(t, v, "repeated vertex");
        }
        const int64_t orient = orientOf(mesh, v);
        if (orient <= 0) return tetProblem(t, v, "not positive");
        volume += orient;
        for (uint32_t f = 0; f < 4; ++f) {
            const uint32_t n = mesh.neighbours[t][f];
            if (n == kNoTet) continue;
            if (n >= mesh.slotCount() || !mesh.inUse(n)) return tetProblem(t, v, "neighbour is not a tet");
            const auto back = std::find(mesh.neighbours[n].begin(), mesh.neighbours[n].end(), t);
            if (back == mesh.neighbours[n].end()) return tetProblem(t, v, "neighbour link not symmetric");
            if (sortedFace(mesh.vertices[n], uint32_t(back - mesh.neighbours[n].begin())) != sortedFace(v, f))
                return tetProblem(t, v, "neighbour across a different face");
        }
        for (uint32_t f = 0; f < 4; ++f) faces.push_back({sortedFace(v, f), t, f});
    }
    for (uint32_t t : free_slots)
        if (t >= mesh.slotCount() || mesh.inUse(t)) return "a listed free slot is in use or out of range";

    std::sort(faces.begin(), faces.end());
    for (size_t i = 0; i < faces.size();) {
        size_t j = i;
        while (j < faces.size() && faces[j].vertices == faces[i].vertices) ++j;
        const FaceRecord& f = faces[i];
        const std::string where = tetProblem(f.tet, mesh.vertices[f.tet], "face " + std::to_string(f.face));
        if (j - i > 2) return where + " shared by more than two tets";
        if (j - i == 2) {
            if (mesh.neighbours[f.tet][f.face] != faces[i + 1].tet) return where + " not linked to the tet sharing it";
        } else {
            if (!onOneBoxSide(mesh, f.vertices)) return where + " has no second tet but is inside the box";
            if (mesh.neighbours[f.tet][f.face] != kNoTet) return where + " on the box's side has a neighbour";
        }
        i = j;
    }
    const __int128 box = __int128(6) * (mesh.size[0] - 1) * (mesh.size[1] - 1) * (mesh.size[2] - 1);
    if (volume != box) return "the tets' volumes do not sum to the box's";
    return "";
}

}  // namespace ddt
