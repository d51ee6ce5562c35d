// Locked sides (Mesh::locked_sides): what a tile of a simplification shares with its
// neighbours stays, vertex for vertex and colour for colour, in both simplifiers.
#include <catch2/catch.hpp>

#include "greedy_simplify.h"
#include "parallel_simplify.h"
#include "test_support.h"

using namespace ddt;
using namespace ddt::test;

namespace {

// The ids of the grid vertices on the sides `sides` (rectangleSides' bits) of a w × h grid,
// found here from their coordinates.
std::vector<uint32_t> verticesOnSides(uint32_t w, uint32_t h, uint32_t sides) {
    std::vector<uint32_t> ids;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            if ((sides & 1 && x == 0) || (sides & 2 && x == w - 1) || (sides & 4 && y == 0) || (sides & 8 && y == h - 1))
                ids.push_back(y * w + x);
    return ids;
}

using Simplifier = SimplifyStats (*)(Mesh&, Image&, uint32_t, double);
SimplifyStats serial(Mesh& mesh, Image& values, uint32_t target, double) { return simplifySerial(mesh, values, target); }
SimplifyStats parallel(Mesh& mesh, Image& values, uint32_t target, double) { return simplifyParallel(mesh, values, target); }

}  // namespace

TEST_CASE("locked sides: their vertices stay where they are, with their pixels' colours") {
    const Image photo = photoPiece();
    const uint32_t w = photo.width, h = photo.height;
    for (auto [simplifier, name] : {std::pair{Simplifier(serial), "serial"}, std::pair{Simplifier(parallel), "parallel"}}) {
        for (uint32_t locked : {0b0010u, 0b1010u, 0b1111u}) {
            INFO(name << " simplifier, locked sides " << locked);
            Mesh mesh = optimisedGridMesh(photo);
            mesh.locked_sides = locked;
            Image values = photo;
            const uint32_t target = w * h / 10;
            const SimplifyStats stats = simplifier(mesh, values, target, 0.0);
            CHECK(checkMesh(mesh) == "");
            CHECK(stats.vertices_after == target);  // the photograph's interior has vertices enough to spare
            const std::vector<bool> used = usedVertices(mesh);
            const std::vector<uint32_t> kept = verticesOnSides(w, h, locked);
            uint32_t moved = 0, recoloured = 0, gone = 0;
            for (uint32_t v : kept) {
                gone += !used[v];
                moved += !(positionOf(mesh, v) == gridPosition(v, w));
                for (uint32_t k = 0; k < photo.channels; ++k)
                    recoloured += values.pixels[size_t(v) * photo.channels + k] != photo.pixels[size_t(v) * photo.channels + k];
            }
            CHECK(gone == 0);
            CHECK(moved == 0);
            CHECK(recoloured == 0);
            // An unlocked side is simplified as before: some of its vertices go.
            const std::vector<uint32_t> free_side = verticesOnSides(w, h, ~locked & 0b1111u);
            uint32_t free_gone = 0;
            for (uint32_t v : free_side) free_gone += !used[v];
            if (!free_side.empty()) CHECK(free_gone > 0);
        }
    }
}
