// The flip gains and costs on meshes with explicit vertex positions (core/image/mesh.h; the
// formulas' Places, glsl/image/sederberg.h): positions at the pixel centres give the grid's numbers
// bit for bit, a hand-made mesh off the grid gives the plane formulas' gain, the costs scale
// with the positions as the formulas predict, and the Vulkan kernels follow core's gains and
// flips step by step on a jittered grid.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "cost.h"
#include "flip_gains.h"
#include "lawson.h"
#include "mesh.h"
#include "stepwise_check.h"
#include "test_support.h"
#include "vulkan_backend.h"

namespace {

using namespace ddt;

const CostFunction kCosts[] = {CostFunction::sederberg, CostFunction::variance, CostFunction::face_scf};

// The width × height grid's mesh with explicit positions: interior vertices moved off their
// pixel centres by up to ±`jitter` (in 1/kPositionOne px) along each axis, the border's kept,
// so that the hull stays the rectangle. A move that would turn a triangle of the vertex's
// round is dropped (with jitter below 0.5 px that is rare but possible: a vertex and the
// opposite side can each move ~0.42 px towards each other, beyond the 0.71 px between them).
Mesh jitteredGrid(uint32_t width, uint32_t height, int32_t jitter, std::mt19937& rng) {
    Mesh mesh = buildGridMesh(width, height);
    makePositionsExplicit(mesh);
    const std::vector<Triangle> triangles = listTriangles(mesh);
    std::uniform_int_distribution<int32_t> step(-jitter, jitter);
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        if (rectangleSides(mesh, v) != 0) continue;
        const Position old = mesh.positions[v];
        mesh.positions[v] = {old.x + step(rng), old.y + step(rng)};
        const bool positive = std::all_of(triangles.begin(), triangles.end(), [&](const Triangle& t) {
            return orientationSign(mesh, t.v0, t.v1, t.v2) > 0;
        });
        if (!positive) mesh.positions[v] = old;
    }
    return mesh;
}

// The same pixels as an n × 1 image: pixel k is still vertex k's value, and nothing may read
// the image's width as the vertices' (a point mesh's values come in any shape).
Image asRow(const Image& image) {
    Image row = image;
    row.width = image.width * image.height;
    row.height = 1;
    return row;
}


// Written here from the definitions, independently of glsl/: a triangle of points (x, y, z).
struct Point {
    double x, y, z;
};
using Tri = std::array<Point, 3>;

// The slope (a, b) of the plane z = a x + b y + c through a triangle's points: Cramer's rule
// on the 3 × 3 system [x y 1] (a b c)ᵀ = z.
std::array<double, 2> slopeOf(const Tri& t) {
    const Point &p = t[0], &q = t[1], &r = t[2];
    const double det = p.x * (q.y - r.y) - p.y * (q.x - r.x) + (q.x * r.y - r.x * q.y);
    const double a = p.z * (q.y - r.y) - p.y * (q.z - r.z) + (q.z * r.y - r.z * q.y);
    const double b = p.x * (q.z - r.z) - p.z * (q.x - r.x) + (q.x * r.z - r.x * q.z);
    return {a / det, b / det};
}

double areaOf(const Tri& t) {
    return std::abs((t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[2].x - t[0].x) * (t[1].y - t[0].y)) / 2;
}

// Sederberg's cost of an edge between two triangles: |∇1| |∇2| − ∇1 · ∇2.
double scfBetween(const Tri& t1, const Tri& t2) {
    const auto g1 = slopeOf(t1), g2 = slopeOf(t2);
    return std::hypot(g1[0], g1[1]) * std::hypot(g2[0], g2[1]) - (g1[0] * g2[0] + g1[1] * g2[1]);
}

bool samePoint(const Point& p, const Point& q) { return p.x == q.x && p.y == q.y; }

// Whether triangles i and j share a side (two corners).
bool shareSide(const Tri& s, const Tri& t) {
    int shared = 0;
    for (const Point& p : s)
        for (const Point& q : t) shared += samePoint(p, q);
    return shared == 2;
}

// The cost of a triangulation, from the definitions (core/image/cost.h): Sederberg's the sum of the
// SCF over interior edges; face-SCF Σ area(T) · (Σ of T's edges' SCF, 0 on the hull) / 3;
// variance Σ area(T) · (population variance of T's three values).
double costOf(const std::vector<Tri>& mesh, CostFunction cost) {
    double total = 0.0;
    for (size_t i = 0; i < mesh.size(); ++i) {
        if (cost == CostFunction::variance) {
            const double mean = (mesh[i][0].z + mesh[i][1].z + mesh[i][2].z) / 3;
            double squares = 0.0;
            for (const Point& p : mesh[i]) squares += (p.z - mean) * (p.z - mean);
            total += areaOf(mesh[i]) * squares / 3;
            continue;
        }
        for (size_t j = 0; j < mesh.size(); ++j) {
            if (j == i || !shareSide(mesh[i], mesh[j])) continue;
            const double scf = scfBetween(mesh[i], mesh[j]);
            // Sederberg: each interior edge once (from its lower triangle); face-SCF: a third
            // of it in each of its two triangles.
            if (cost == CostFunction::sederberg) total += j > i ? scf : 0.0;
            else total += areaOf(mesh[i]) * scf / 3;
        }
    }
    return total;
}

}  // namespace

TEST_CASE("positions: explicit pixel centres give the grid's gains, costs and flips bit for bit", "[positions]") {
    std::mt19937 rng(21);
    // RGBA: the alpha channel's gains go through the places too.
    const Image image = test::randomImage(rng, 23, 17, 4);
    const CostField field = costFieldOf(image);
    Mesh grid = buildGridMesh(23, 17);
    test::flipRandomEdges(grid, rng, 300);  // not only the grid's diagonals
    Mesh placed = grid;
    makePositionsExplicit(placed);
    REQUIRE(placed.positions.size() == 23 * 17);
    for (CostFunction cost : kCosts) {
        INFO(costFunctionName(cost));
        FlipGains grid_gains(grid, field, cost), placed_gains(placed, field, cost);
        CHECK(meshCost(placed, field, cost) == meshCost(grid, field, cost));
        CHECK(placed_gains.total() == grid_gains.total());
        for (uint32_t e = 0; e < grid.edgeCount(); ++e) {
            INFO("edge " << e);
            CHECK(edgeCost(placed, field, e, cost) == edgeCost(grid, field, e, cost));
            const double gain = flipGainOf(grid, field, e, cost);
            CHECK(flipGainOf(placed, field, e, cost) == gain);
            CHECK(placed_gains.gainOf(e) == gain);
            CHECK(grid_gains.gainOf(e) == gain);
        }
        Mesh grid_optimised = grid, placed_optimised = placed;
        const OptimizeStats by_grid = optimizeSerial(grid_optimised, field, {.cost = cost});
        const OptimizeStats by_places = optimizeSerial(placed_optimised, field, {.cost = cost});
        CHECK(by_places.flips == by_grid.flips);
        CHECK(by_places.iterations == by_grid.iterations);
        CHECK(by_places.cost_init == by_grid.cost_init);
        CHECK(by_places.cost_final == by_grid.cost_final);
        CHECK(by_grid.flips > 0);
        placed_optimised.positions.clear();
        CHECK(test::sameRecords(placed_optimised, grid_optimised));
    }
}

TEST_CASE("positions: a mesh off the grid has the plane formulas' gain", "[positions]") {
    // Four corners of the square [0, 4]² and a vertex c inside it at (1.25, 1.75), as a fan
    // of four triangles (y grows downwards, so the positive triangles run clockwise here):
    //
    //   v0 (0,0) ---------------- v1 (4,0)
    //     |  `.                 .'  |
    //     |     `.           .'     |
    //     |        c (1.25, 1.75)   |
    //     |      .'    `-.          |
    //     |   .'           `-.      |
    //   v3 (0,4) ---------------- v2 (4,4)
    //
    // Edge c–v2's quadrilateral c, v1, v2, v3 is convex (c lies on v0's side of the diagonal
    // v1–v3), and its flip gives v1–v3.
    const uint32_t c = 4;
    const std::vector<uint32_t> triangles = {0, 1, c, 1, 2, c, 2, 3, c, 3, 0, c};
    Mesh mesh = meshFromTriangles(5, 5, triangles);
    const double xs[5] = {0, 4, 4, 0, 1.25}, ys[5] = {0, 0, 4, 4, 1.75};
    for (uint32_t v = 0; v < 5; ++v)
        mesh.positions.push_back({int32_t(xs[v] * kPositionOne), int32_t(ys[v] * kPositionOne)});
    REQUIRE(checkMesh(mesh, MeshHull::convex) == "");
    // The values, exact in float; vertex k's is pixel k of a 5 × 1 image.
    const float zs[5] = {0.125f, 0.75f, 0.25f, 0.875f, 0.5f};
    const CostField field = costFieldOf(test::makeImage(5, 1, 1, {zs, zs + 5}));
    auto point = [&](uint32_t v) { return Point{xs[v], ys[v], double(zs[v])}; };
    auto triangle = [&](uint32_t p, uint32_t q, uint32_t r) { return Tri{point(p), point(q), point(r)}; };
    const std::vector<Tri> before = {triangle(0, 1, c), triangle(1, 2, c), triangle(2, 3, c), triangle(3, 0, c)};
    const std::vector<Tri> after = {triangle(0, 1, c), triangle(3, 0, c), triangle(1, 2, 3), triangle(1, 3, c)};
    const uint32_t e = test::edgeBetween(mesh, c, 2);
    REQUIRE(e != kNone);
    for (CostFunction cost : kCosts) {
        INFO(costFunctionName(cost));
        // The two sides compute the same numbers by different formulas (Cramer's rule here,
        // glsl/image/sederberg.h's one division per edge there): on values and slopes of order 1
        // they differ by rounding, ~1e-15.
        const double expected = costOf(before, cost) - costOf(after, cost);
        CHECK(std::abs(expected) > 0.01);  // a gain, or a loss, that matters
        CHECK(std::abs(meshCost(mesh, field, cost) - costOf(before, cost)) <= 1e-12);
        const double gain = flipGainOf(mesh, field, e, cost);
        CHECK(std::abs(gain - expected) <= 1e-12);
        FlipGains gains(mesh, field, cost);
        CHECK(gains.gainOf(e) == gain);  // the serial optimizer's fast path, bit for bit
        Mesh flipped = mesh;
        flipEdge(flipped, e);
        REQUIRE(checkMesh(flipped, MeshHull::convex) == "");
        CHECK(std::abs(meshCost(flipped, field, cost) - costOf(after, cost)) <= 1e-12);
    }
    // A hull edge cannot flip, nor can the spoke c–v0: c lies inside the triangle v0, v1, v3,
    // so the quadrilateral v0, v1, c, v3 is reflex at c.
    const double refused = -std::numeric_limits<double>::infinity();
    CHECK(flipGainOf(mesh, field, test::edgeBetween(mesh, 0, 1)) == refused);
    CHECK(flipGainOf(mesh, field, test::edgeBetween(mesh, c, 0)) == refused);
    CHECK(flipGainOf(mesh, field, test::edgeBetween(mesh, c, 1)) > refused);
}

TEST_CASE("positions: scaling the positions scales each cost's gain as its formula predicts", "[positions]") {
    // Positions scaled by s, values kept: every plane z = a x + b y + c becomes
    // z = (a / s) x + (b / s) y + c, so gradients scale by 1 / s and areas by s². Hence
    // Sederberg's SCF |∇1| |∇2| − ∇1 · ∇2 scales by 1 / s², face-SCF's SCF · area by 1, and
    // variance's area · Var(z) by s², and so does every gain, a difference of such sums.
    // For s = 2 this holds bit for bit: multiplying by a power of two commutes with rounding
    // (no overflow or underflow here), and every operation of the formulas is a product,
    // quotient, square root, sum or difference of such scaled numbers (sqrt of 16 x is 4 sqrt x
    // exactly). For s = 3 each operation rounds differently: the gains agree up to rounding of
    // their terms, ~1e-16 relative to the costs summed, whatever the gain's own size.
    std::mt19937 rng(22);
    const uint32_t w = 15, h = 12;
    const Mesh mesh = jitteredGrid(w, h, kPositionOne * 3 / 10, rng);
    REQUIRE(checkMesh(mesh, MeshHull::rectangle) == "");
    const CostField field = costFieldOf(test::randomImage(rng, w, h, 1));
    for (int32_t s : {2, 3}) {
        Mesh scaled = mesh;
        scaled.width = s * (w - 1) + 1;
        scaled.height = s * (h - 1) + 1;
        for (Position& p : scaled.positions) p = {s * p.x, s * p.y};
        REQUIRE(checkMesh(scaled, MeshHull::convex) == "");  // fewer positions than w · h: no grid
        for (CostFunction cost : kCosts) {
            INFO(costFunctionName(cost) << " × " << s);
            const double factor = cost == CostFunction::sederberg  ? 1.0 / (s * s)
                                  : cost == CostFunction::variance ? double(s * s)
                                                                   : 1.0;
            const double tolerance = s == 2 ? 0.0 : 1e-14 * factor * meshCost(mesh, field, cost);
            FlipGains gains(scaled, field, cost);
            uint32_t convex = 0;
            for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
                const double gain = flipGainOf(mesh, field, e, cost), scaled_gain = flipGainOf(scaled, field, e, cost);
                CHECK(gains.gainOf(e) == scaled_gain);
                if (std::isinf(gain)) {
                    CHECK(std::isinf(scaled_gain));  // convexity does not depend on the scale
                    continue;
                }
                ++convex;
                CHECK(std::abs(scaled_gain - factor * gain) <= tolerance);
            }
            CHECK(convex > mesh.edgeCount() / 2);
            CHECK(std::abs(meshCost(scaled, field, cost) - factor * meshCost(mesh, field, cost)) <=
                  tolerance * mesh.edgeCount());
        }
    }
}

TEST_CASE("positions: the serial optimizer on a jittered grid keeps a valid mesh and reaches a local optimum",
          "[positions]") {
    std::mt19937 rng(23);
    const uint32_t w = 24, h = 18;
    const Mesh initial = jitteredGrid(w, h, kPositionOne * 3 / 10, rng);
    REQUIRE(checkMesh(initial, MeshHull::convex) == "");
    REQUIRE(checkMesh(initial, MeshHull::rectangle) == "");
    const CostField field = costFieldOf(asRow(test::randomImage(rng, w, h, 3)));
    for (CostFunction cost : kCosts) {
        INFO(costFunctionName(cost));
        Mesh mesh = initial;
        // The fast gains are flipGainOf's bit for bit, on the way too.
        FlipGains gains(mesh, field, cost);
        for (uint32_t e = 0; e < mesh.edgeCount(); ++e) CHECK(gains.gainOf(e) == flipGainOf(mesh, field, e, cost));
        LawsonOptions options;
        options.cost = cost;
        options.after_sweep = [&](uint32_t, const Mesh& now) {
            FlipGains now_gains(now, field, cost);
            for (uint32_t e = 0; e < now.edgeCount(); e += 7) CHECK(now_gains.gainOf(e) == flipGainOf(now, field, e, cost));
        };
        const OptimizeStats stats = optimizeSerial(mesh, field, options);
        CHECK(checkMesh(mesh, MeshHull::rectangle) == "");
        CHECK(stats.flips > 0);
        CHECK(stats.cost_final < stats.cost_init);
        CHECK(stats.cost_init == meshCost(initial, field, cost));
        CHECK(stats.cost_final == meshCost(mesh, field, cost));
        CHECK(test::largestGain(mesh, field, cost) <= kFlipGainThreshold);
        // The positions matter: the grid's places give other flips.
        Mesh on_grid = initial;
        on_grid.positions.clear();
        optimizeSerial(on_grid, field, {.cost = cost});
        on_grid.positions = initial.positions;
        CHECK_FALSE(test::sameRecords(on_grid, mesh));
    }
}

TEST_CASE("positions: Vulkan's flips on a jittered grid equal core's, step by step", "[positions][vulkan]") {
    std::mt19937 rng(24);
    const uint32_t w = 26, h = 19;
    const Mesh mesh = jitteredGrid(w, h, kPositionOne * 3 / 10, rng);
    REQUIRE(checkMesh(mesh, MeshHull::convex) == "");
    const Image values = asRow(test::randomImage(rng, w, h, 3));
    for (CostFunction cost : kCosts) {
        INFO(costFunctionName(cost));
        test::checkVulkanStepwise(values, mesh, cost);
    }
}

TEST_CASE("positions: explicit pixel centres give the grid's optimization on the device", "[positions][vulkan]") {
    std::mt19937 rng(25);
    const Image image = test::randomImage(rng, 21, 16, 2);  // grey and alpha
    Mesh placed = buildGridMesh(21, 16);
    makePositionsExplicit(placed);
    for (CostFunction cost : kCosts) {
        INFO(costFunctionName(cost));
        VulkanOptions options;
        options.validation = true;
        options.cost = cost;
        VulkanBackend backend(options);
        backend.prepare(image);
        const std::vector<double> grid_costs = backend.deviceEdgeCosts();
        const OptimizeStats by_grid = backend.optimize();
        const Mesh from_grid = backend.mesh();
        backend.prepareFrom(image, placed);
        CHECK(backend.deviceEdgeCosts() == grid_costs);
        const OptimizeStats by_places = backend.optimize();
        Mesh from_places = backend.mesh();
        CHECK(from_places.positions == placed.positions);
        from_places.positions.clear();
        CHECK(test::sameRecords(from_places, from_grid));
        CHECK(by_places.flips == by_grid.flips);
        CHECK(by_places.iterations == by_grid.iterations);
        CHECK(by_places.cost_init == by_grid.cost_init);
        CHECK(by_places.cost_final == by_grid.cost_final);
        CHECK(by_grid.flips > 0);
        CHECK(backend.validationMessages() == 0);
    }
}
