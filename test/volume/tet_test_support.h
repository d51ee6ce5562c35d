// Fields and meshes the tetrahedral tests share (test/volume/test_tet_*.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <functional>

#include "tet_cost.h"
#include "tet_mesh.h"

namespace ddt::test {

using Size = std::array<uint32_t, 3>;

// The field of value(x, y, z) on the grid, normalized by its range.
TetCostField fieldOf(const Size& size, const std::function<double(uint32_t, uint32_t, uint32_t)>& value,
                     std::array<double, 3> spacing = {1.0, 1.0, 1.0});

// 1 inside the sphere of radius `radius` around the n³ grid's centre, 0 outside.
TetCostField sphereField(uint32_t n, double radius);

// A sharp plane across the n³ grid's diagonal: 1 where x + 2y + 3z >= 2.5 n, else 0.
TetCostField slantedPlaneField(uint32_t n, std::array<double, 3> spacing = {1.0, 1.0, 1.0});

// Independent values drawn from `seed`, with `levels` levels (many exact ties), normalized.
TetCostField randomField(const Size& size, uint32_t seed, uint32_t levels);

// The same tets without free slots: in-use records renumbered in slot order.
TetMesh compacted(const TetMesh& mesh);

// Every record equal: slots, vertices, neighbours, free slots.
bool sameMesh(const TetMesh& a, const TetMesh& b);

// Sets every tet's neighbours by matching faces (sorted vertex triples), for meshes built by hand.
void linkNeighbours(TetMesh& mesh);

}  // namespace ddt::test
