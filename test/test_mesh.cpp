#include <catch2/catch.hpp>

#include "mesh.h"

TEST_CASE("mesh: the grid triangulation is valid") {
    for (auto [w, h] : {std::pair{2u, 2u}, {3u, 2u}, {2u, 5u}, {7u, 4u}}) {
        ddt::Mesh mesh = ddt::buildGridMesh(w, h);
        CHECK(ddt::checkMesh(mesh) == "");
    }
}
