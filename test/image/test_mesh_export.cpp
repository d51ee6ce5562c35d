// The mesh as files hold it (core/image/indexed_mesh.h, core/image/stitched_mesh.h, core/io/mesh_file.h):
// the border ring, the y-up counter-clockwise convention, the surface it describes, the
// stitching of tiles and the PLY and OBJ layouts.
#include <catch2/catch.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <random>
#include <sstream>

#include "backend.h"
#include "delaunay.h"
#include "delaunay/point_mesh.h"
#include "sampled_render.h"
#include "greedy_simplify.h"
#include "indexed_mesh.h"
#include "mesh_file.h"
#include "render.h"
#include "stitched_mesh.h"
#include "test_support.h"
#include "tiled_upscale.h"

using namespace ddt;
using namespace ddt::test;

namespace {

std::vector<uint32_t> triangleIds(const Mesh& mesh) {
    std::vector<uint32_t> ids;
    forEachTriangle(mesh, [&](const Triangle& t) { ids.insert(ids.end(), {t.v0, t.v1, t.v2}); });
    return ids;
}

// A valid mesh of a width × height grid that is not the initial one.
Mesh shuffledMesh(uint32_t width, uint32_t height, std::mt19937& rng) {
    Mesh mesh = buildGridMesh(width, height);
    flipRandomEdges(mesh, rng, width * height);
    REQUIRE(triangulationProblem(mesh).empty());
    return mesh;
}

// Twice the signed area of face f in the file's frame (y up): positive = counter-clockwise.
double twiceFaceArea(const IndexedMesh& m, uint32_t f) {
    const double* p = &m.positions[3 * size_t(m.faces[3 * f])];
    const double* q = &m.positions[3 * size_t(m.faces[3 * f + 1])];
    const double* r = &m.positions[3 * size_t(m.faces[3 * f + 2])];
    return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
}

// The mesh's value at (x, y) (file frame), by barycentric interpolation in the face that
// holds the point; nullopt if no face does.
std::optional<std::vector<double>> valueInside(const IndexedMesh& m, double x, double y) {
    for (uint32_t f = 0; f < m.faceCount(); ++f) {
        const double* p = &m.positions[3 * size_t(m.faces[3 * f])];
        const double* q = &m.positions[3 * size_t(m.faces[3 * f + 1])];
        const double* r = &m.positions[3 * size_t(m.faces[3 * f + 2])];
        const double area = twiceFaceArea(m, f);
        const double l0 = ((q[0] - x) * (r[1] - y) - (q[1] - y) * (r[0] - x)) / area;
        const double l1 = ((r[0] - x) * (p[1] - y) - (r[1] - y) * (p[0] - x)) / area;
        const double l2 = 1.0 - l0 - l1;
        const double slack = 1e-12;  // a point on a shared edge belongs to either face
        if (l0 < -slack || l1 < -slack || l2 < -slack) continue;
        std::vector<double> value(m.channels);
        for (uint32_t k = 0; k < m.channels; ++k)
            value[k] = l0 * m.colours[size_t(m.faces[3 * f]) * m.channels + k] +
                       l1 * m.colours[size_t(m.faces[3 * f + 1]) * m.channels + k] +
                       l2 * m.colours[size_t(m.faces[3 * f + 2]) * m.channels + k];
        return value;
    }
    return std::nullopt;
}

// valueInside, failing the test where no face holds the point.
std::vector<double> valueAt(const IndexedMesh& m, double x, double y) {
    std::optional<std::vector<double>> value = valueInside(m, x, y);
    if (!value) FAIL("no face holds (" << x << ", " << y << ")");
    return *value;
}

// Where the renderer samples output column or row i of a mesh with explicit positions
// (render.h), in output pixels: the input coordinate (i + 0.5)·in/out − 0.5, clamped into
// [0, in − 1] and rounded (half up) to 1/1024 pixel, in exact integers, then mapped to the
// output as the files map positions.
double snappedSample(uint32_t i, uint32_t in, uint32_t out) {
    const int64_t u = std::clamp<int64_t>((2 * int64_t(i) + 1) * in - out, 0, 2 * int64_t(out) * (in - 1));
    const int64_t snapped = (u * 1024 + out) / (2 * int64_t(out));
    return (double(snapped) / 1024 + 0.5) * out / in;
}

std::string fileBytes(MeshFormat format, const IndexedMesh& mesh) {
    std::string bytes;
    writeMesh(format, mesh, "test", [&](const char* data, size_t size) { bytes.append(data, size); });
    return bytes;
}

}  // namespace

TEST_CASE("mesh export: a ring out to the image rectangle, faces counter-clockwise with y up") {
    std::mt19937 rng(7);
    const uint32_t w = 5, h = 4;
    const Mesh mesh = shuffledMesh(w, h, rng);
    const Image image = randomImage(rng, w, h, 3);
    const OutputSize out{13, 10};  // factors 2.6 and 2.5
    const IndexedMesh m = indexedMeshOf(triangleIds(mesh), mesh.positions, image, out);

    // The grid's vertices, one copy per hull vertex, the four corners; the ring has two
    // triangles per hull segment and two per corner.
    CHECK(m.vertexCount() == w * h + 2 * (w + h) + 4);
    CHECK(m.faceCount() == 2 * (w - 1) * (h - 1) + 4 * (w - 1) + 4 * (h - 1) + 8);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const double* p = &m.positions[3 * size_t(y * w + x)];
            CHECK(p[0] == (x + 0.5) * 2.6);
            CHECK(p[1] == 10.0 - (y + 0.5) * 2.5);
            CHECK(p[2] == 0.0);
        }
    double area = 0.0;
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (uint32_t f = 0; f < m.faceCount(); ++f) {
        INFO("face " << f);
        CHECK(twiceFaceArea(m, f) > 0.0);
        area += twiceFaceArea(m, f) / 2;
        for (int k = 0; k < 3; ++k) ++directed[{m.faces[3 * f + k], m.faces[3 * f + (k + 1) % 3]}];
    }
    CHECK(area == Approx(13.0 * 10.0).epsilon(1e-12));  // a sum of double products: rounding only
    // Each edge once each way round, but for the rectangle's sides, which have one face.
    auto onRectangle = [&](uint32_t a, uint32_t b) {
        const double* p = &m.positions[3 * size_t(a)];
        const double* q = &m.positions[3 * size_t(b)];
        return (p[0] == q[0] && (p[0] == 0.0 || p[0] == 13.0)) || (p[1] == q[1] && (p[1] == 0.0 || p[1] == 10.0));
    };
    for (const auto& [edge, count] : directed) {
        CHECK(count == 1);
        if (!onRectangle(edge.first, edge.second)) CHECK(directed.count({edge.second, edge.first}) == 1);
    }
    for (double coordinate : m.positions) CHECK(coordinate >= 0.0);
}

TEST_CASE("mesh export: the file's linear surface is plain DDT's render, out to the image border") {
    std::mt19937 rng(11);
    const uint32_t w = 7, h = 5;
    const Mesh mesh = shuffledMesh(w, h, rng);
    const Image image = randomImage(rng, w, h, 3);
    const OutputSize out{17, 12};
    const Image plain = renderImage(mesh, image, out);
    const IndexedMesh m = indexedMeshOf(triangleIds(mesh), mesh.positions, image, out);
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x) {
            INFO("output pixel (" << x << ", " << y << ")");
            const std::vector<double> value = valueAt(m, x + 0.5, out.height - (y + 0.5));
            for (uint32_t k = 0; k < 3; ++k)
                // Both are the same interpolation in double, with weights computed in different
                // ways (the renderer's exact integers, this test's coordinates), rounded to float.
                CHECK(value[k] == Approx(plain.row(y)[x * 3 + k]).margin(1e-6));
        }
}

TEST_CASE("mesh export: a simplified mesh's file has only its vertices and is still its render") {
    std::mt19937 rng(13);
    const uint32_t w = 12, h = 9;
    Mesh mesh = shuffledMesh(w, h, rng);
    Image values = randomImage(rng, w, h, 3);
    simplifySerial(mesh, values, 30);
    REQUIRE(checkMesh(mesh) == "");
    const OutputSize out{29, 20};
    const Image plain = renderImage(mesh, values, out);
    const IndexedMesh m = indexedMeshOf(triangleIds(mesh), mesh.positions, values, out);
    // The kept vertices, a copy of each kept hull vertex (a corner on two sides), four corners.
    uint32_t hull = 0;
    std::vector<bool> used(w * h, false);
    for (const EdgeVertices& v : mesh.vertices) used[v.a] = used[v.b] = true;
    for (uint32_t v = 0; v < w * h; ++v) {
        const uint32_t x = v % w, y = v / w;
        if (used[v]) hull += uint32_t(x == 0) + uint32_t(x == w - 1) + uint32_t(y == 0) + uint32_t(y == h - 1);
    }
    CHECK(m.vertexCount() == usedVertexCount(mesh) + hull + 4);
    double area = 0.0;
    for (uint32_t f = 0; f < m.faceCount(); ++f) {
        CHECK(twiceFaceArea(m, f) > 0.0);
        area += twiceFaceArea(m, f) / 2;
    }
    CHECK(area == Approx(double(out.width) * out.height).epsilon(1e-12));  // rounding only, as above
    // The vertices moved off the pixel centres: the renderer samples at snapped positions.
    CHECK(std::count_if(mesh.positions.begin(), mesh.positions.end(),
                        [](Position p) { return p.x % 1024 != 0 || p.y % 1024 != 0; }) > 0);
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x) {
            INFO("output pixel (" << x << ", " << y << ")");
            const std::vector<double> value =
                valueAt(m, snappedSample(x, w, out.width), out.height - snappedSample(y, h, out.height));
            for (uint32_t k = 0; k < 3; ++k) CHECK(value[k] == Approx(plain.row(y)[x * 3 + k]).margin(1e-6));  // as above
        }
}

// A mask's mesh (pixel ids, implicit positions, a frame-sized values image) and a point
// file's (explicit positions, one value per vertex): the file holds exactly the mesh's
// vertices and triangles, no ring, and wherever an output sample lies in the samples' hull
// its surface is the raster's.
TEST_CASE("mesh export: a sample mesh's file holds its samples, and inside their hull is their render") {
    std::mt19937 rng(17);
    const uint32_t w = 11, h = 8;
    const OutputSize frame{w, h}, out{27, 19};
    // Known: every pixel but the top-left corner's triangle and a 3 × 2 hole.
    std::vector<uint32_t> known;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            if (x + y >= 3 && !(x >= 5 && x < 8 && y >= 3 && y < 5)) known.push_back(y * w + x);
    const Mesh mask_mesh = delaunayOfPixels(w, h, known);
    const Image mask_values = randomImage(rng, w, h, 3);

    PointSamples points;
    points.channels = 3;
    std::uniform_real_distribution<double> px(0.0, w - 1.0), py(0.0, h - 1.0), level(0.0, 1.0);
    for (int i = 0; i < 40; ++i) {
        points.x.push_back(px(rng));
        points.y.push_back(py(rng));
        for (int k = 0; k < 3; ++k) points.values.push_back(float(level(rng)));
    }
    const SampledPoints sampled = triangulatePoints(points, {w, h});
    REQUIRE(!sampled.mesh.positions.empty());  // the explicit form

    const std::pair<const Mesh*, const Image*> cases[] = {{&mask_mesh, &mask_values}, {&sampled.mesh, &sampled.values}};
    for (const auto& [mesh, values] : cases) {
        const bool positioned = !mesh->positions.empty();
        INFO((positioned ? "point file" : "mask"));
        const IndexedMesh m = indexedSampleMeshOf(*mesh, *values, frame, out);
        CHECK(m.vertexCount() == (positioned ? 40u : uint32_t(known.size())));
        CHECK(m.faceCount() == listTriangles(*mesh).size());
        for (uint32_t f = 0; f < m.faceCount(); ++f) CHECK(twiceFaceArea(m, f) > 0.0);
        const Image raster = renderSampledMesh(*mesh, *values, out);
        uint32_t inside = 0;
        for (uint32_t y = 0; y < out.height; ++y)
            for (uint32_t x = 0; x < out.width; ++x) {
                INFO("output pixel (" << x << ", " << y << ")");
                // The renderer samples explicit positions on its 1/1024-pixel grid.
                const double fx = positioned ? snappedSample(x, w, out.width) : x + 0.5;
                const double fy = positioned ? snappedSample(y, h, out.height) : y + 0.5;
                const std::optional<std::vector<double>> value = valueInside(m, fx, out.height - fy);
                if (!value) continue;
                ++inside;
                for (uint32_t k = 0; k < 3; ++k)
                    // The same interpolation with weights computed two ways, rounded to float.
                    CHECK((*value)[k] == Approx(raster.row(y)[x * 3 + k]).margin(1e-6));
            }
        CHECK(inside > out.width * out.height / 3);  // the hull holds a good share of the samples
        CHECK(inside < out.width * out.height);      // and not all: no ring to the rectangle
    }
}

TEST_CASE("mesh export: straight colours, and z from luma times the height") {
    const Image rgba = makeImage(2, 2, 4, {0.25f, 0.1f, 0.05f, 0.5f, 0.0f, 0.0f, 0.0f, 0.0f,  //
                                           0.2f, 0.4f, 0.6f, 1.0f, 0.3f, 0.3f, 0.3f, 0.6f});
    const IndexedMesh m = indexedMeshOf(triangleIds(buildGridMesh(2, 2)), {}, rgba, {4, 4}, 10.0);
    REQUIRE(m.channels == 4);
    const float expected[4][4] = {{0.5f, 0.2f, 0.1f, 0.5f}, {0, 0, 0, 0}, {0.2f, 0.4f, 0.6f, 1.0f}, {0.5f, 0.5f, 0.5f, 0.6f}};
    for (int v = 0; v < 4; ++v)
        for (int k = 0; k < 4; ++k)  // a float division: rounding only
            CHECK(m.colours[4 * v + k] == Approx(expected[v][k]).epsilon(1e-6));
    // Approx's default (about 1e-5 relative): the colours behind z are float divisions.
    CHECK(m.positions[2] == Approx(10.0 * (0.2126 * 0.5 + 0.7152 * 0.2 + 0.0722 * 0.1)));
    CHECK(m.positions[3 * 3 + 2] == Approx(10.0 * 0.5));

    const Image grey = makeImage(2, 2, 1, {0.0f, 0.25f, 0.5f, 1.0f});
    const IndexedMesh g = indexedMeshOf(triangleIds(buildGridMesh(2, 2)), {}, grey, {6, 6}, 4.0);
    for (uint32_t v = 0; v < g.vertexCount(); ++v) CHECK(g.positions[3 * size_t(v) + 2] == Approx(4.0 * g.colours[v]));
}

TEST_CASE("stitched mesh: the check finds gaps, overlaps and inverted triangles") {
    // The initial 3 × 3 grid, each cell split by its (x, y)–(x+1, y+1) diagonal:
    //   0 - 1 - 2
    //   | \ | \ |
    //   3 - 4 - 5
    //   | \ | \ |
    //   6 - 7 - 8
    const std::vector<uint32_t> grid = triangleIds(buildGridMesh(3, 3));
    REQUIRE(grid.size() == 8 * 3);
    CHECK(StitchedMesh::check(grid, 3, 3).empty());

    std::vector<uint32_t> gap(grid.begin() + 3, grid.end());
    CHECK_THAT(StitchedMesh::check(gap, 3, 3), Catch::Contains("area"));
    std::vector<uint32_t> twice = grid;
    twice.insert(twice.end(), grid.begin(), grid.begin() + 3);
    CHECK_THAT(StitchedMesh::check(twice, 3, 3), Catch::Contains("area"));
    // Same area, but the cell 0-1-4-3 covered twice by its two diagonals' triangles and the
    // cell 4-5-8-7 not at all.
    std::vector<uint32_t> moved;
    for (size_t t = 0; t < grid.size(); t += 3) {
        std::vector<uint32_t> tri(grid.begin() + t, grid.begin() + t + 3);
        std::sort(tri.begin(), tri.end());
        if (tri == std::vector<uint32_t>{4, 5, 8} || tri == std::vector<uint32_t>{4, 7, 8}) continue;
        moved.insert(moved.end(), grid.begin() + t, grid.begin() + t + 3);
    }
    // (0, 1, 3) and (1, 4, 3): the cell's other diagonal, positive in the y-down frame.
    moved.insert(moved.end(), {0, 1, 3, 1, 4, 3});
    CHECK_FALSE(StitchedMesh::check(moved, 3, 3).empty());
    std::vector<uint32_t> inverted = grid;
    std::swap(inverted[1], inverted[2]);
    CHECK_THAT(StitchedMesh::check(inverted, 3, 3), Catch::Contains("not positive"));
}

TEST_CASE("stitched mesh: tiles' meshes join into the untiled mesh") {
    const Image photo = photoCrop();
    const OutputSize out = scaledOutputSize(photo.width, photo.height, 2.0);
    std::unique_ptr<Backend> backend = makeCpuBackend();
    auto trianglesWith = [&](uint32_t tile) {
        StitchedMesh stitched(photo.width, photo.height);
        TileOptions options;
        options.tile = tile;
        options.mesh = &stitched;
        PackedImage packed(photo);
        upscaleRows(*backend, packed, out, options, [](OutputRows&&) {});
        return stitched.take();
    };
    const std::vector<uint32_t> untiled = trianglesWith(0), tiled = trianglesWith(64);
    CHECK(StitchedMesh::check(untiled, photo.width, photo.height).empty());
    CHECK(StitchedMesh::check(tiled, photo.width, photo.height).empty());
    CHECK(tiled == untiled);
}

TEST_CASE("mesh files: PLY is binary little-endian with the input's colour type") {
    std::mt19937 rng(3);
    Image image = randomImage(rng, 4, 3, 3);
    for (SampleType type : {SampleType::UInt8, SampleType::UInt16, SampleType::Float}) {
        INFO(sampleTypeName(type));
        image.sample_type = type;
        const IndexedMesh m = indexedMeshOf(triangleIds(buildGridMesh(4, 3)), {}, image, {8, 6});
        const std::string bytes = fileBytes(MeshFormat::Ply, m);
        const size_t header_end = bytes.find("end_header\n");
        REQUIRE(header_end != std::string::npos);
        const std::string header = bytes.substr(0, header_end);
        const char* type_name = type == SampleType::UInt8 ? "uchar" : type == SampleType::UInt16 ? "ushort" : "float";
        const size_t colour_size = type == SampleType::UInt8 ? 1 : type == SampleType::UInt16 ? 2 : 4;
        CHECK_THAT(header, Catch::StartsWith("ply\nformat binary_little_endian 1.0\ncomment test\n"));
        CHECK_THAT(header, Catch::Contains("element vertex " + std::to_string(m.vertexCount()) +
                                           "\nproperty float x\nproperty float y\nproperty float z\nproperty " +
                                           type_name + " red\nproperty " + type_name + " green\nproperty " + type_name +
                                           " blue\nelement face " + std::to_string(m.faceCount()) +
                                           "\nproperty list uchar int vertex_indices\n"));
        const char* body = bytes.data() + header_end + std::strlen("end_header\n");
        const size_t vertex_size = 12 + 3 * colour_size;
        REQUIRE(bytes.size() == size_t(body - bytes.data()) + m.vertexCount() * vertex_size + m.faceCount() * 13);
        for (uint32_t v = 0; v < m.vertexCount(); ++v) {
            float xyz[3];
            std::memcpy(xyz, body + v * vertex_size, 12);
            for (int k = 0; k < 3; ++k) CHECK(xyz[k] == float(m.positions[3 * v + k]));
            const char* colour = body + v * vertex_size + 12;
            for (int k = 0; k < 3; ++k) {
                const float value = m.colours[3 * v + k];
                if (type == SampleType::UInt8) CHECK(uint8_t(colour[k]) == std::lround(value * 255.0f));
                if (type == SampleType::UInt16) {
                    uint16_t level;
                    std::memcpy(&level, colour + 2 * k, 2);
                    CHECK(level == std::lround(value * 65535.0f));
                }
                if (type == SampleType::Float) {
                    float stored;
                    std::memcpy(&stored, colour + 4 * k, 4);
                    CHECK(stored == value);
                }
            }
        }
        const char* faces = body + m.vertexCount() * vertex_size;
        for (uint32_t f = 0; f < m.faceCount(); ++f) {
            CHECK(faces[13 * f] == 3);
            int32_t ids[3];
            std::memcpy(ids, faces + 13 * f + 1, 12);
            for (int k = 0; k < 3; ++k) CHECK(uint32_t(ids[k]) == m.faces[3 * f + k]);
        }
    }
}

TEST_CASE("mesh files: OBJ has v x y z r g b lines and 1-based faces, numbers read back exactly") {
    std::mt19937 rng(5);
    const Image image = randomImage(rng, 3, 3, 2);  // grey + alpha: r = g = b = grey, alpha dropped
    const IndexedMesh m = indexedMeshOf(triangleIds(buildGridMesh(3, 3)), {}, image, {7, 7});
    std::istringstream lines(fileBytes(MeshFormat::Obj, m));
    std::string line;
    std::getline(lines, line);
    CHECK(line == "# test");
    uint32_t v = 0, f = 0;
    while (std::getline(lines, line)) {
        std::istringstream fields(line);
        std::string kind;
        fields >> kind;
        if (kind == "v") {
            REQUIRE(v < m.vertexCount());
            for (int k = 0; k < 3; ++k) {
                std::string text;
                fields >> text;
                double value;
                std::from_chars(text.data(), text.data() + text.size(), value);
                CHECK(value == m.positions[3 * v + k]);
            }
            for (int k = 0; k < 3; ++k) {
                std::string text;
                fields >> text;
                float value;
                std::from_chars(text.data(), text.data() + text.size(), value);
                CHECK(value == m.colours[2 * v]);
            }
            std::string extra;
            CHECK_FALSE(fields >> extra);  // no alpha
            ++v;
        } else {
            REQUIRE(kind == "f");
            REQUIRE(f < m.faceCount());
            for (int k = 0; k < 3; ++k) {
                uint32_t id;
                fields >> id;
                CHECK(id == m.faces[3 * f + k] + 1);
            }
            ++f;
        }
    }
    CHECK(v == m.vertexCount());
    CHECK(f == m.faceCount());
}

TEST_CASE("mesh files: the format comes from the extension or a bare name, any case") {
    CHECK(meshFormatOf("a/b.ply") == MeshFormat::Ply);
    CHECK(meshFormatOf("B.OBJ") == MeshFormat::Obj);
    CHECK(meshFormatOf("ply") == MeshFormat::Ply);
    CHECK(meshFormatOf(".obj") == MeshFormat::Obj);
    CHECK_FALSE(meshFormatOf("mesh.stl"));
    CHECK(meshFormatOf("x.Svg") == MeshFormat::Svg);
    CHECK_FALSE(meshFormatOf("svgz"));
}

TEST_CASE("mesh files: SVG gradients reproduce a grey mesh's colours at its corners") {
    std::mt19937 rng(9);
    const Image grey = randomImage(rng, 6, 5, 1);
    const IndexedMesh m = indexedMeshOf(triangleIds(shuffledMesh(6, 5, rng)), {}, grey, {15, 12});
    const std::string svg = fileBytes(MeshFormat::Svg, m);
    CHECK_THAT(svg, Catch::Contains("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"15\" height=\"12\" viewBox=\"0 0 15 12\" "
                                    "shape-rendering=\"crispEdges\">"));
    // Each path, with the gradient just before it if its fill refers to one. (sscanf: GCC 12's
    // <regex> trips -Wmaybe-uninitialized in the sanitizer builds, which treat warnings as errors.)
    std::istringstream lines(svg);
    std::string line, previous;
    uint32_t face = 0;
    while (std::getline(lines, line)) {
        double px[3], py[3];
        char fill[64];
        if (std::sscanf(line.c_str(), "<path d=\"M%lf %lfL%lf %lfL%lf %lfZ\" fill=\"%63[^\"]\"/>", &px[0], &py[0], &px[1],
                        &py[1], &px[2], &py[2], fill) != 7) {
            previous = line;
            continue;
        }
        REQUIRE(face < m.faceCount());
        INFO("face " << face << ": " << previous << " " << line);
        unsigned id = 0, low = 0, high = 0;
        double x1 = 0, y1 = 0, x2 = 0, y2 = 0;
        const bool has_gradient =
            std::sscanf(previous.c_str(),
                        "<linearGradient id=\"g%u\" gradientUnits=\"userSpaceOnUse\" x1=\"%lf\" y1=\"%lf\" x2=\"%lf\" "
                        "y2=\"%lf\"><stop stop-color=\"#%2x%*4x\"/><stop offset=\"1\" stop-color=\"#%2x%*4x\"/>",
                        &id, &x1, &y1, &x2, &y2, &low, &high) == 7;
        if (!has_gradient) CHECK(fill[0] == '#');  // a flat colour, where the triangle's is constant
        if (has_gradient) {
            CHECK(id == face);
            CHECK(std::string(fill) == "url(#g" + std::to_string(face) + ")");
        }
        for (int i = 0; i < 3; ++i) {
            const uint32_t v = m.faces[3 * face + i];
            const double x = px[i], y = py[i];
            CHECK(x == Approx(m.positions[3 * v]).margin(1e-6));  // written with 8 significant digits
            CHECK(y == Approx(12.0 - m.positions[3 * v + 1]).margin(1e-6));
            double value;
            if (has_gradient) {
                const double t = std::clamp(((x - x1) * (x2 - x1) + (y - y1) * (y2 - y1)) /
                                                ((x2 - x1) * (x2 - x1) + (y2 - y1) * (y2 - y1)),
                                            0.0, 1.0);
                value = (low + t * (double(high) - low)) / 255.0;
            } else {
                value = std::stoi(std::string(fill).substr(1, 2), nullptr, 16) / 255.0;
            }
            // A grey triangle's colour varies along one direction, which the gradient takes;
            // its two stops are rounded to 8 bits (half a level each).
            CHECK(value == Approx(m.colours[v]).margin(1.0 / 255.0));
        }
        ++face;
        previous.clear();
    }
    CHECK(face == m.faceCount());
}
