#include "test_support.h"

#include "cost.h"
#include "edge_collapse.h"
#include "image_file.h"
#include "lawson.h"
#include "user_error.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <sstream>

namespace ddt::test {

Image makeImage(uint32_t width, uint32_t height, uint32_t channels, std::vector<float> pixels) {
    assert(pixels.size() == size_t(width) * height * channels);
    Image image;
    image.width = width;
    image.height = height;
    image.channels = channels;
    image.pixels = std::move(pixels);
    return image;
}

Image greyImage(const std::vector<std::vector<float>>& rows) {
    std::vector<float> pixels;
    for (const auto& row : rows) {
        assert(row.size() == rows[0].size());
        pixels.insert(pixels.end(), row.begin(), row.end());
    }
    return makeImage(uint32_t(rows[0].size()), uint32_t(rows.size()), 1, std::move(pixels));
}

Image randomImage(std::mt19937& rng, uint32_t width, uint32_t height, uint32_t channels, uint32_t levels) {
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    std::uniform_int_distribution<uint32_t> level(0, levels > 1 ? levels - 1 : 0);
    std::vector<float> pixels(size_t(width) * height * channels);
    for (float& p : pixels) p = levels > 1 ? float(level(rng)) / float(levels - 1) : value(rng);
    return makeImage(width, height, channels, std::move(pixels));
}

uint32_t edgeBetween(const Mesh& mesh, uint32_t p, uint32_t q) {
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
        const EdgeVertices& v = mesh.vertices[e];
        if ((v.a == p && v.b == q) || (v.a == q && v.b == p)) return e;
    }
    return kNone;
}

int64_t twiceArea(const Mesh& mesh, uint32_t p, uint32_t q, uint32_t r) {
    const int64_t w = mesh.width;
    const int64_t px = p % w, py = p / w, qx = q % w, qy = q / w, rx = r % w, ry = r / w;
    return (qx - px) * (ry - py) - (qy - py) * (rx - px);
}

bool quadIsStrictlyConvex(const Mesh& mesh, uint32_t e) {
    const EdgeVertices& v = mesh.vertices[e];
    if (v.l == kNone || v.r == kNone) return false;
    return twiceArea(mesh, v.r, v.b, v.l) > 0 && twiceArea(mesh, v.l, v.a, v.r) > 0;
}

uint32_t flipRandomEdges(Mesh& mesh, std::mt19937& rng, uint32_t count) {
    std::uniform_int_distribution<uint32_t> pick(0, mesh.edgeCount() - 1);
    uint32_t done = 0;
    // Bounded tries: a tiny mesh may have few convex quads at some moment.
    for (uint32_t tries = 0; done < count && tries < 20 * count; ++tries) {
        uint32_t e = pick(rng);
        if (!flipIsConvex(flipStencil(mesh, e), placesOf(mesh))) continue;
        flipEdge(mesh, e);
        ++done;
    }
    return done;
}

Mesh scrambledGridMesh(uint32_t width, uint32_t height, std::mt19937& rng) {
    Mesh mesh = buildGridMesh(width, height);
    flipRandomEdges(mesh, rng, 4 * width * height);
    return mesh;
}

Mesh movedMesh(uint32_t width, uint32_t height, std::mt19937& rng) {
    Mesh mesh = buildGridMesh(width, height);
    flipRandomEdges(mesh, rng, 4 * width * height);
    makePositionsExplicit(mesh);
    const std::vector<Triangle> triangles = listTriangles(mesh);
    std::uniform_int_distribution<int32_t> step(-kPositionOne * 9 / 20, kPositionOne * 9 / 20);
    for (int pass = 0; pass < 3; ++pass)
        for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
            const uint32_t sides = rectangleSides(mesh, v);
            if (sides != 0 && (sides & (sides - 1)) != 0) continue;  // a corner
            const Position old = mesh.positions[v];
            const int32_t dx = step(rng), dy = step(rng);
            mesh.positions[v] = {old.x + ((sides & 3) ? 0 : dx), old.y + ((sides & 12) ? 0 : dy)};
            const bool positive = std::all_of(triangles.begin(), triangles.end(), [&](const Triangle& t) {
                return orientationSign(mesh, t.v0, t.v1, t.v2) > 0;
            });
            if (!positive) mesh.positions[v] = old;
        }
    return mesh;
}

namespace {

bool onHull(const Mesh& mesh, uint32_t p, uint32_t q) {
    const uint32_t w = mesh.width, h = mesh.height;
    const uint32_t px = p % w, py = p / w, qx = q % w, qy = q / w;
    const bool unit = (px == qx && (py + 1 == qy || qy + 1 == py)) || (py == qy && (px + 1 == qx || qx + 1 == px));
    const bool same_side = (px == qx && (px == 0 || px == w - 1)) || (py == qy && (py == 0 || py == h - 1));
    return unit && same_side;
}

bool joinsPair(const Mesh& mesh, uint32_t e, uint32_t p, uint32_t q) {
    if (e >= mesh.edgeCount()) return false;
    const EdgeVertices& v = mesh.vertices[e];
    return (v.a == p && v.b == q) || (v.a == q && v.b == p);
}

std::array<uint32_t, 3> canonicalTriangle(uint32_t p, uint32_t q, uint32_t r) {
    if (q < p && q < r) return {q, r, p};
    if (r < p && r < q) return {r, p, q};
    return {p, q, r};
}

}  // namespace

std::string triangulationProblem(const Mesh& mesh) {
    const uint64_t w = mesh.width, h = mesh.height;
    std::ostringstream out;
    if (w < 2 || h < 2) return "too small";
    const uint64_t expected_edges = (w - 1) * h + w * (h - 1) + (w - 1) * (h - 1);
    if (mesh.vertices.size() != expected_edges || mesh.neighbours.size() != expected_edges) return "edge count";

    std::set<std::pair<uint32_t, uint32_t>> pairs;
    std::map<std::array<uint32_t, 3>, int> seen;  // triangle -> how many edge sides list it
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) {
        const EdgeVertices& v = mesh.vertices[e];
        const EdgeNeighbours& n = mesh.neighbours[e];
        out << "edge " << e << ": ";
        if (v.a >= w * h || v.b >= w * h || v.a == v.b) return out.str() + "bad main vertices";
        if (!pairs.insert({std::min(v.a, v.b), std::max(v.a, v.b)}).second) return out.str() + "duplicate";
        const bool hull = onHull(mesh, v.a, v.b);
        const int sides = (v.l != kNone) + (v.r != kNone);
        if (sides != (hull ? 1 : 2)) return out.str() + "wrong number of triangles";
        // Left (a, b, l) with links b–l, l–a; right (b, a, r) with links a–r, r–b.
        if (v.l != kNone) {
            if (v.l >= w * h || twiceArea(mesh, v.a, v.b, v.l) <= 0) return out.str() + "left triangle not positive";
            if (!joinsPair(mesh, n.bl, v.b, v.l) || !joinsPair(mesh, n.la, v.l, v.a)) return out.str() + "left links";
            ++seen[canonicalTriangle(v.a, v.b, v.l)];
        } else if (n.bl != kNone || n.la != kNone) {
            return out.str() + "links without a left triangle";
        }
        if (v.r != kNone) {
            if (v.r >= w * h || twiceArea(mesh, v.b, v.a, v.r) <= 0) return out.str() + "right triangle not positive";
            if (!joinsPair(mesh, n.ar, v.a, v.r) || !joinsPair(mesh, n.rb, v.r, v.b)) return out.str() + "right links";
            ++seen[canonicalTriangle(v.b, v.a, v.r)];
        } else if (n.ar != kNone || n.rb != kNone) {
            return out.str() + "links without a right triangle";
        }
        out.str("");
    }
    if (seen.size() != 2 * (w - 1) * (h - 1)) return "wrong number of triangles";
    int64_t twice_area = 0;
    for (const auto& [t, count] : seen) {
        if (count != 3) return "a triangle not listed by exactly its three edges";
        twice_area += twiceArea(mesh, t[0], t[1], t[2]);
    }
    if (twice_area != int64_t(2 * (w - 1) * (h - 1))) return "area not conserved";
    return "";
}

bool sameRecords(const Mesh& a, const Mesh& b) {
    if (a.width != b.width || a.height != b.height || a.edgeCount() != b.edgeCount()) return false;
    for (uint32_t e = 0; e < a.edgeCount(); ++e) {
        const EdgeVertices &u = a.vertices[e], &v = b.vertices[e];
        const EdgeNeighbours &m = a.neighbours[e], &n = b.neighbours[e];
        if (u.a != v.a || u.b != v.b || u.l != v.l || u.r != v.r) return false;
        if (m.bl != n.bl || m.la != n.la || m.ar != n.ar || m.rb != n.rb) return false;
    }
    return a.positions == b.positions;
}

std::string userErrorOf(const std::function<void()>& action) {
    try {
        action();
    } catch (const UserError& error) {
        return error.what();
    }
    return "";
}

bool samePixels(std::span<const float> a, std::span<const float> b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (!(a[i] == b[i])) return false;
    return true;
}

Image photoCrop() {
    const Image photo = readImage(std::string(DDTUP_TEST_DATA) + "/../../bench/data/real/astronaut.png");
    const uint32_t x0 = 120, y0 = 40, w = 300, h = 200;
    REQUIRE(photo.width >= x0 + w);
    REQUIRE(photo.height >= y0 + h);
    std::vector<float> pixels;
    for (uint32_t y = y0; y < y0 + h; ++y)
        pixels.insert(pixels.end(), photo.row(y) + size_t(x0) * photo.channels,
                      photo.row(y) + size_t(x0 + w) * photo.channels);
    return makeImage(w, h, photo.channels, pixels);
}

Image photoPiece() {
    const Image photo = photoCrop();
    std::vector<float> pixels;
    for (uint32_t y = 60; y < 130; ++y)
        pixels.insert(pixels.end(), photo.row(y) + 100 * photo.channels, photo.row(y) + 200 * photo.channels);
    return makeImage(100, 70, photo.channels, pixels);
}

Mesh optimisedGridMesh(const Image& image) {
    Mesh mesh = buildGridMesh(image.width, image.height);
    optimizeSerial(mesh, costFieldOf(image));
    return mesh;
}

void renderTileInto(Backend& backend, const Image& image, OutputSize out, const Tile& tile, std::vector<float>& whole) {
    const RenderWindow window{image.width,    image.height,   out,           tile.crop.x0, tile.crop.y0,
                              tile.output.x0, tile.output.x1, tile.output.y0, tile.output.y1};
    std::vector<float> rows(size_t(window.width()) * window.height() * image.channels);
    backend.renderWindow(window, rows.data());
    const size_t row_floats = size_t(window.width()) * image.channels;
    for (uint32_t y = 0; y < window.height(); ++y)
        std::copy_n(rows.data() + y * row_floats, row_floats,
                    whole.data() + (size_t(window.y_begin + y) * out.width + window.x_begin) * image.channels);
}

Agreement compareSamples(const std::vector<float>& a, const std::vector<float>& b) {
    REQUIRE(a.size() == b.size());
    Agreement agreement;
    size_t close = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        const float d = std::fabs(a[i] - b[i]);
        REQUIRE(std::isfinite(d));
        agreement.max_difference = std::max(agreement.max_difference, d);
        close += d <= 1.0f / 255.0f;
    }
    agreement.within_one_level = double(close) / double(a.size());
    return agreement;
}

Mesh centreFanMesh(uint32_t side) {
    const uint32_t centre = side / 2 * side + side / 2;
    Mesh mesh = buildGridMesh(side, side);
    VertexEdges edges(mesh);
    for (bool collapsed = true; collapsed;) {
        collapsed = false;
        std::vector<uint32_t> at_centre;
        forEachEdgeAt(mesh, edges, centre, [&](uint32_t f) { at_centre.push_back(f); });
        for (uint32_t f : at_centre) {
            const Collapse into_centre{f, mesh.vertices[f].a == centre};
            if (!canCollapse(mesh, edges, into_centre)) continue;
            collapseEdge(mesh, edges, into_centre);
            collapsed = true;
            break;
        }
    }
    return mesh;
}

}  // namespace ddt::test
