// Helpers shared by the core tests: small images made in memory, edge look-up by endpoints,
// random legal flips, and an invariant checker written independently of core's checkMesh
// (its own orientation arithmetic), so the two can vouch for each other.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <span>
#include <vector>

#include "backend.h"
#include "image.h"
#include "mesh.h"
#include "tiling.h"

namespace ddt::test {

// Path of a fixture in test/data.
inline std::string testDataPath(const std::string& name) {
    std::string path = DDTUP_TEST_DATA;  // appended, not `+`: GCC 12 warns falsely about the temporaries
    path += '/';
    path += name;
    return path;
}

// A width × height image made in memory; `pixels` row-major, `channels` floats per pixel.
Image makeImage(uint32_t width, uint32_t height, uint32_t channels, std::vector<float> pixels);

// A grey image from rows of values written as a picture: rows[y][x].
Image greyImage(const std::vector<std::vector<float>>& rows);

// Random values in [0, 1]; with levels > 0 only the values k / (levels − 1), which creates
// many exact ties in the cost.
Image randomImage(std::mt19937& rng, uint32_t width, uint32_t height, uint32_t channels, uint32_t levels = 0);

// Vertex id of pixel centre (x, y).
inline uint32_t vertexAt(const Mesh& mesh, uint32_t x, uint32_t y) { return y * mesh.width + x; }

// Id of the edge joining vertices p and q, or kNone (a search over the records).
uint32_t edgeBetween(const Mesh& mesh, uint32_t p, uint32_t q);

// Twice the signed area of (p, q, r), computed here from the vertex ids (y grows downwards;
// positive = the mesh's positive orientation).
int64_t twiceArea(const Mesh& mesh, uint32_t p, uint32_t q, uint32_t r);

// Whether e has two triangles and the quadrilateral a, r, b, l is strictly convex (both
// new triangles (r, b, l) and (l, a, r) positive), computed here.
bool quadIsStrictlyConvex(const Mesh& mesh, uint32_t e);

// Flips `count` random edges whose quadrilateral is strictly convex; returns the flips done.
uint32_t flipRandomEdges(Mesh& mesh, std::mt19937& rng, uint32_t count);

// The width × height grid mesh after 4 · width · height random convex flips: long, thin
// triangles of every direction, each still of area 1/2 (every pixel centre stays a vertex).
Mesh scrambledGridMesh(uint32_t width, uint32_t height, std::mt19937& rng);

// A width × height grid mesh scrambled by random convex flips whose vertices then move off
// the pixel centres (explicit positions): interior ones by up to 0.45 pixels along each axis,
// border ones along their side, corners not at all; each move kept only if every triangle
// stays positive. A general mesh, as simplification's new vertices make.
Mesh movedMesh(uint32_t width, uint32_t height, std::mt19937& rng);

// Independent invariant check: every edge joins two distinct vertices and appears once;
// each side's triangle is positive and listed by all three of its edges with the right
// neighbour links; hull edges have one triangle, others two; 2(w−1)(h−1) triangles whose
// areas add up to (w−1)(h−1). Returns "" or the first problem.
std::string triangulationProblem(const Mesh& mesh);

// Records equal field by field.
bool sameRecords(const Mesh& a, const Mesh& b);  // records and explicit positions

// The message of the UserError `action` throws; "" when it throws none (other exceptions pass).
std::string userErrorOf(const std::function<void()>& action);

// Exact float equality of two pixel arrays (NaN never equal).
bool samePixels(std::span<const float> a, std::span<const float> b);

// A 300×200 crop of bench/data's astronaut photo: texture, soft and hard edges.
Image photoCrop();

// A 100 × 70 piece of photoCrop(), for the slower reference algorithms.
Image photoPiece();

// The mesh the serial optimizer makes for `image`.
Mesh optimisedGridMesh(const Image& image);

// The side × side grid after every neighbour of its centre vertex (side / 2, side / 2) was
// collapsed into it while that was legal (core/simplify/edge_collapse.h), one at a time: a fan
// around the centre that kMaxCollapseValence stops from reaching the border (side ≥ 20).
// Removed edges are left marked, not compacted.
Mesh centreFanMesh(uint32_t side);

// Renders `tile`'s output with `backend`, prepared on the tile's crop of `image`, into its
// place in `whole`, an untiled output of size `out`.
void renderTileInto(Backend& backend, const Image& image, OutputSize out, const Tile& tile, std::vector<float>& whole);

// How closely two renderings of one image agree, sample by sample (for tiled vs untiled).
struct Agreement {
    float max_difference = 0.0f;
    double within_one_level = 0.0;  // share of samples that differ by at most 1/255
};
// Fails the calling test when the sizes differ or a difference is not finite.
Agreement compareSamples(const std::vector<float>& a, const std::vector<float>& b);

}  // namespace ddt::test
