#include "tet_test_support.h"

#include <algorithm>
#include <map>
#include <random>

namespace ddt::test {

TetCostField fieldOf(const Size& size, const std::function<double(uint32_t, uint32_t, uint32_t)>& value,
                     std::array<double, 3> spacing) {
    std::vector<double> raw;
    for (uint32_t z = 0; z < size[2]; ++z)
        for (uint32_t y = 0; y < size[1]; ++y)
            for (uint32_t x = 0; x < size[0]; ++x) raw.push_back(value(x, y, z));
    TetCostField field;
    field.size = size;
    field.spacing = spacing;
    field.values = normalizedValues(raw);
    return field;
}

TetCostField sphereField(uint32_t n, double radius) {
    const double c = (n - 1) / 2.0;
    return fieldOf({n, n, n}, [&](uint32_t x, uint32_t y, uint32_t z) {
        return (x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c) <= radius * radius ? 1.0 : 0.0;
    });
}

TetCostField slantedPlaneField(uint32_t n, std::array<double, 3> spacing) {
    return fieldOf({n, n, n}, [n](uint32_t x, uint32_t y, uint32_t z) { return x + 2 * y + 3 * z >= 2.5 * n ? 1.0 : 0.0; },
                   spacing);
}

TetCostField randomField(const Size& size, uint32_t seed, uint32_t levels) {
    std::mt19937 rng(seed);
    return fieldOf(size, [&](uint32_t, uint32_t, uint32_t) { return double(rng() % levels); });
}

TetMesh compacted(const TetMesh& mesh) {
    std::vector<uint32_t> renumbered(mesh.slotCount(), kNoTet);
    TetMesh out;
    out.size = mesh.size;
    for (uint32_t t = 0; t < mesh.slotCount(); ++t)
        if (mesh.inUse(t)) {
            renumbered[t] = out.slotCount();
            out.vertices.push_back(mesh.vertices[t]);
        }
    for (uint32_t t = 0; t < mesh.slotCount(); ++t)
        if (mesh.inUse(t)) {
            TetNeighbours n = mesh.neighbours[t];
            for (uint32_t& across : n)
                if (across != kNoTet) across = renumbered[across];
            out.neighbours.push_back(n);
        }
    return out;
}

bool sameMesh(const TetMesh& a, const TetMesh& b) {
    return a.size == b.size && a.vertices == b.vertices && a.neighbours == b.neighbours && a.free_slots == b.free_slots;
}

void linkNeighbours(TetMesh& mesh) {
    std::map<std::array<uint32_t, 3>, std::pair<uint32_t, uint32_t>> open;  // face → (tet, face index)
    mesh.neighbours.assign(mesh.slotCount(), {kNoTet, kNoTet, kNoTet, kNoTet});
    for (uint32_t t = 0; t < mesh.slotCount(); ++t) {
        if (!mesh.inUse(t)) continue;
        for (uint32_t f = 0; f < 4; ++f) {
            std::array<uint32_t, 3> face;
            for (uint32_t k = 0, j = 0; k < 4; ++k)
                if (k != f) face[j++] = mesh.vertices[t][k];
            std::sort(face.begin(), face.end());
            const auto found = open.find(face);
            if (found == open.end()) {
                open[face] = {t, f};
                continue;
            }
            mesh.neighbours[t][f] = found->second.first;
            mesh.neighbours[found->second.first][found->second.second] = t;
            open.erase(found);
        }
    }
}

}  // namespace ddt::test
