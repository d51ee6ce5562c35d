// Point files (core/io/point_file.h): scattered colour samples read from CSV and PLY, every
// layout and scale the header promises, and one refusal per kind of bad input.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "mesh_file.h"
#include "point_file.h"
#include "temp_folder.h"

using namespace ddt;

namespace {

std::string writeFile(const TempFolder& folder, const std::string& name, const std::string& bytes) {
    const std::string path = folder / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

// The message of the UserError that reading `path` throws; fails the test if there is none.
std::string refusal(const std::string& path) {
    try {
        readPointFile(path);
    } catch (const UserError& error) {
        return error.what();
    }
    FAIL("reading " << path << " throws no UserError");
    return "";
}

// Reading `path` fails with one line that names the file first and contains `reason`.
void checkRefused(const std::string& path, const std::string& reason) {
    const std::string message = refusal(path);
    INFO(message);
    CHECK(message.starts_with(path + ": "));
    CHECK(message.find(reason) != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
}

// Binary data in a chosen byte order (the tests run on little-endian machines, as ddtup does).
struct Bytes {
    std::string bytes;
    bool big_endian = false;
    template <typename T>
    Bytes& operator()(T value) {
        char raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T));
        if (big_endian) std::reverse(raw, raw + sizeof(T));
        bytes.append(raw, sizeof(T));
        return *this;
    }
};

constexpr float k8(int level) { return float(level) / 255.0f; }
constexpr float k16(int level) { return float(level) / 65535.0f; }

using Values = std::vector<float>;
using Coordinates = std::vector<double>;

}  // namespace

TEST_CASE("point file: .csv and .ply in any case are point files", "[point-file]") {
    CHECK(isPointFilePath("a/b/points.csv"));
    CHECK(isPointFilePath("POINTS.CSV"));
    CHECK(isPointFilePath("mesh.Ply"));
    CHECK_FALSE(isPointFilePath("image.png"));
    CHECK_FALSE(isPointFilePath("csv"));
    CHECK_FALSE(isPointFilePath("points.csv.gz"));
}

// ---- CSV ----

TEST_CASE("point file: CSV of RGB values in [0, 1]", "[point-file]") {
    TempFolder folder;
    const PointSamples points = readPointFile(writeFile(folder, "p.csv", "0,0,1,0.5,0\n2.5,3.25,0.25,0.75,1\n10,7,0,0,0.125\n"));
    CHECK(points.channels == 3);
    CHECK(points.sample_type == SampleType::Float);
    CHECK(points.x == Coordinates{0, 2.5, 10});
    CHECK(points.y == Coordinates{0, 3.25, 7});
    CHECK(points.values == Values{1, 0.5f, 0, 0.25f, 0.75f, 1, 0, 0, 0.125f});
}

TEST_CASE("point file: CSV of RGBA, grey and grey + alpha", "[point-file]") {
    TempFolder folder;
    const PointSamples rgba = readPointFile(writeFile(folder, "rgba.csv", "1,2,0.1,0.2,0.3,0.4\n3,4,1,1,1,0"));
    CHECK(rgba.channels == 4);
    CHECK(rgba.x == Coordinates{1, 3});
    CHECK(rgba.y == Coordinates{2, 4});
    CHECK(rgba.values == Values{0.1f, 0.2f, 0.3f, 0.4f, 1, 1, 1, 0});

    const PointSamples grey = readPointFile(writeFile(folder, "grey.csv", "0,0,0.5\n1,0,0.25\n0,1,1\n"));
    CHECK(grey.channels == 1);
    CHECK(grey.size() == 3);
    CHECK(grey.values == Values{0.5f, 0.25f, 1});

    const PointSamples grey_alpha = readPointFile(writeFile(folder, "ga.csv", "0,0,0.5,1\n4,5,0.25,0\n"));
    CHECK(grey_alpha.channels == 2);
    CHECK(grey_alpha.x == Coordinates{0, 4});
    CHECK(grey_alpha.values == Values{0.5f, 1, 0.25f, 0});
}

TEST_CASE("point file: a CSV header line, comments, blank lines, CRLF and spaces", "[point-file]") {
    TempFolder folder;
    const PointSamples points = readPointFile(writeFile(folder, "p.csv",
                                                        "\xEF\xBB\xBF# made by hand, with a byte order mark\r\n"
                                                        "\r\n"
                                                        "x, y, r, g, b\r\n"
                                                        "  0 ,\t1.5 , 0.5,0.25 ,1  \r\n"
                                                        "   # an indented comment\r\n"
                                                        "   \t \r\n"
                                                        "+2,1e1, 5e-1 ,0,.5\r\n"));
    CHECK(points.channels == 3);
    CHECK(points.sample_type == SampleType::Float);
    CHECK(points.x == Coordinates{0, 2});
    CHECK(points.y == Coordinates{1.5, 10});
    CHECK(points.values == Values{0.5f, 0.25f, 1, 0.5f, 0, 0.5f});
}

TEST_CASE("point file: CSV negative zeros read as zeros", "[point-file]") {
    TempFolder folder;
    const PointSamples points = readPointFile(writeFile(folder, "p.csv", "-0,-0.0,-0\n"));
    REQUIRE(points.size() == 1);
    CHECK_FALSE(std::signbit(points.x[0]));
    CHECK_FALSE(std::signbit(points.y[0]));
    CHECK_FALSE(std::signbit(points.values[0]));
}

TEST_CASE("point file: CSV duplicates are kept as listed", "[point-file]") {
    TempFolder folder;
    const PointSamples points = readPointFile(writeFile(folder, "p.csv", "1,1,0.5\n1,1,0.5\n1,1,0.75\n"));
    CHECK(points.size() == 3);
    CHECK(points.values == Values{0.5f, 0.5f, 0.75f});
}

TEST_CASE("point file: CSV whole numbers above 1 are 8-bit levels", "[point-file]") {
    TempFolder folder;
    // Coordinates do not count: only colour values decide the scale.
    const PointSamples levels = readPointFile(writeFile(folder, "levels.csv", "0,0,255,128,0\n300,2,0,1,51.0\n"));
    CHECK(levels.sample_type == SampleType::UInt8);
    CHECK(levels.x == Coordinates{0, 300});
    CHECK(levels.values == Values{1, k8(128), 0, 0, k8(1), k8(51)});

    // Only 0s and 1s: black and white in [0, 1], not levels 0 and 1.
    const PointSamples binary = readPointFile(writeFile(folder, "binary.csv", "0,0,1,0,1\n20,30,0,1,0\n"));
    CHECK(binary.sample_type == SampleType::Float);
    CHECK(binary.values == Values{1, 0, 1, 0, 1, 0});
}

// ---- PLY ----

TEST_CASE("point file: ascii PLY with extra properties and faces after the vertices", "[point-file]") {
    TempFolder folder;
    const std::string path = writeFile(folder, "p.ply",
                                       "ply\n"
                                       "format ascii 1.0\n"
                                       "comment scattered samples\n"
                                       "element vertex 3\n"
                                       "property float x\n"
                                       "property float y\n"
                                       "property float z\n"
                                       "property float nx\n"
                                       "property uchar red\n"
                                       "property uchar green\n"
                                       "property uchar blue\n"
                                       "property int label\n"
                                       "element face 1\n"
                                       "property list uchar int vertex_indices\n"
                                       "end_header\n"
                                       "0 0 7 -1 255 0 51 -40\n"
                                       "4.5 0.25 8 0.5 0 128 1 7\n"
                                       "1 6 9 1e3 10 20 30 0\n"
                                       "3 0 1 2\n");
    const PointSamples points = readPointFile(path);
    CHECK(points.channels == 3);
    CHECK(points.sample_type == SampleType::UInt8);
    CHECK(points.x == Coordinates{0, 4.5, 1});
    CHECK(points.y == Coordinates{0, 0.25, 6});
    CHECK(points.values == Values{1, 0, k8(51), 0, k8(128), k8(1), k8(10), k8(20), k8(30)});
}

TEST_CASE("point file: ascii PLY skips an element with lists before the vertices", "[point-file]") {
    TempFolder folder;
    const std::string path = writeFile(folder, "p.ply",
                                       "ply\r\n"
                                       "format ascii 1.0\r\n"
                                       "element material 2\r\n"
                                       "property list uchar float32 weights\r\n"
                                       "property int id\r\n"
                                       "element vertex 2\r\n"
                                       "property float32 x\r\n"
                                       "property float32 y\r\n"
                                       "property float32 red\r\n"
                                       "property float32 green\r\n"
                                       "property float32 blue\r\n"
                                       "property float32 alpha\r\n"
                                       "end_header\r\n"
                                       "3 0.1 0.2 0.3 7\r\n"
                                       "0 8\r\n"
                                       "1 2 0.5 0.25 0 1\r\n"
                                       "3 4 1 0.125 0.75 0\r\n");
    const PointSamples points = readPointFile(path);
    CHECK(points.channels == 4);
    CHECK(points.sample_type == SampleType::Float);
    CHECK(points.x == Coordinates{1, 3});
    CHECK(points.y == Coordinates{2, 4});
    CHECK(points.values == Values{0.5f, 0.25f, 0, 1, 1, 0.125f, 0.75f, 0});
}

TEST_CASE("point file: binary little-endian PLY of ushort RGBA after an element with lists", "[point-file]") {
    TempFolder folder;
    Bytes data;
    // element `edge` (2 items): list uchar int, then short; skipped by reading each list's length.
    data(uint8_t(2))(int32_t(0))(int32_t(1))(int16_t(-5));
    data(uint8_t(0))(int16_t(9));
    // element vertex: double x, double z, double y, ushort r g b a, float confidence
    data(1.5)(99.0)(2.0)(uint16_t(65535))(uint16_t(0))(uint16_t(1000))(uint16_t(32768))(0.5f);
    data(0.0)(-3.0)(7.25)(uint16_t(1))(uint16_t(2))(uint16_t(3))(uint16_t(4))(1.0f);
    data(uint8_t(3))(int32_t(0))(int32_t(1))(int32_t(1));  // a face after: not read
    const std::string path = writeFile(folder, "p.ply",
                                       "ply\nformat binary_little_endian 1.0\n"
                                       "element edge 2\nproperty list uchar int vertex_index\nproperty short kind\n"
                                       "element vertex 2\nproperty double x\nproperty double z\nproperty double y\n"
                                       "property ushort red\nproperty ushort green\nproperty ushort blue\n"
                                       "property ushort alpha\nproperty float confidence\n"
                                       "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
                                           data.bytes);
    const PointSamples points = readPointFile(path);
    CHECK(points.channels == 4);
    CHECK(points.sample_type == SampleType::UInt16);
    CHECK(points.x == Coordinates{1.5, 0});
    CHECK(points.y == Coordinates{2, 7.25});
    CHECK(points.values == Values{1, 0, k16(1000), k16(32768), k16(1), k16(2), k16(3), k16(4)});
}

TEST_CASE("point file: binary big-endian PLY of float colours", "[point-file]") {
    TempFolder folder;
    Bytes data{"", true};
    data(0.25f)(0.5f)(int32_t(-7))(0.0f)(0.5f)(1.0f);
    data(100.0f)(3.0f)(int32_t(1 << 20))(0.125f)(0.25f)(0.375f);
    const std::string path = writeFile(folder, "p.PLY",
                                       "ply\nformat binary_big_endian 1.0\nelement vertex 2\n"
                                       "property float x\nproperty float y\nproperty int id\n"
                                       "property float red\nproperty float green\nproperty float blue\nend_header\n" +
                                           data.bytes);
    const PointSamples points = readPointFile(path);
    CHECK(points.channels == 3);
    CHECK(points.sample_type == SampleType::Float);
    CHECK(points.x == Coordinates{0.25, 100});
    CHECK(points.y == Coordinates{0.5, 3});
    CHECK(points.values == Values{0, 0.5f, 1, 0.125f, 0.25f, 0.375f});
}

TEST_CASE("point file: a PLY ddtup's mesh writer made reads back", "[point-file]") {
    TempFolder folder;
    // Three vertices and one face, positions exact in float (the writer stores float):
    //   (0.5, 4)  (3.25, 4)
    //   (0.5, 1)
    IndexedMesh mesh;
    mesh.positions = {0.5, 4, 0, 3.25, 4, 0.75, 0.5, 1, 0};
    mesh.faces = {0, 2, 1};
    mesh.out = {4, 5, 0};
    auto write = [&](const std::string& name) {
        std::string bytes;
        writeMesh(MeshFormat::Ply, mesh, "a test mesh", [&](const char* data, size_t size) { bytes.append(data, size); });
        return writeFile(folder, name, bytes);
    };

    SECTION("8-bit RGB") {
        mesh.channels = 3;
        mesh.colour_type = SampleType::UInt8;
        mesh.colours = {k8(255), k8(0), k8(51), k8(1), k8(128), k8(254), k8(0), k8(0), k8(0)};
        const PointSamples points = readPointFile(write("rgb8.ply"));
        CHECK(points.channels == 3);
        CHECK(points.sample_type == SampleType::UInt8);
        CHECK(points.x == Coordinates{0.5, 3.25, 0.5});
        CHECK(points.y == Coordinates{4, 4, 1});
        CHECK(points.values == mesh.colours);
    }
    SECTION("16-bit RGBA") {
        mesh.channels = 4;
        mesh.colour_type = SampleType::UInt16;
        mesh.colours = {k16(65535), k16(0), k16(1000), k16(1), k16(2), k16(3), k16(4), k16(5), k16(0), k16(0), k16(0), k16(0)};
        const PointSamples points = readPointFile(write("rgba16.ply"));
        CHECK(points.channels == 4);
        CHECK(points.sample_type == SampleType::UInt16);
        CHECK(points.x == Coordinates{0.5, 3.25, 0.5});
        CHECK(points.values == mesh.colours);
    }
    SECTION("float grey, stored as red = green = blue") {
        mesh.channels = 1;
        mesh.colour_type = SampleType::Float;
        mesh.colours = {0.1f, 0.7f, 1.0f};
        const PointSamples points = readPointFile(write("grey.ply"));
        CHECK(points.channels == 3);
        CHECK(points.sample_type == SampleType::Float);
        CHECK(points.y == Coordinates{4, 4, 1});
        CHECK(points.values == Values{0.1f, 0.1f, 0.1f, 0.7f, 0.7f, 0.7f, 1, 1, 1});
    }
}

// ---- refusals: files and CSV ----

TEST_CASE("point file: refuses a missing, empty, folder or unknown file", "[point-file]") {
    TempFolder folder;
    checkRefused(folder / "missing.csv", "no such file");
    checkRefused(writeFile(folder, "empty.ply", ""), "empty file");
    std::filesystem::create_directory(folder / "folder.csv");
    checkRefused(folder / "folder.csv", "is a folder");
    checkRefused(writeFile(folder, "points.txt", "0,0,1\n"), "not a point file");
}

TEST_CASE("point file: refuses a CSV without points", "[point-file]") {
    TempFolder folder;
    checkRefused(writeFile(folder, "p.csv", "# nothing\n\nx,y,v\n  \n"), "no points");
    checkRefused(writeFile(folder, "blank.csv", "\n\r\n\n"), "no points");
}

TEST_CASE("point file: refuses a CSV of the wrong column count, naming the line", "[point-file]") {
    TempFolder folder;
    checkRefused(writeFile(folder, "two.csv", "0,0\n"), "line 1: 2 columns");
    checkRefused(writeFile(folder, "seven.csv", "# c\n0,0,1,1,1,1,1\n"), "line 2: 7 columns");
    checkRefused(writeFile(folder, "mixed.csv", "0,0,1,1,1\n\n1,1,1,1\n"), "line 3: 4 columns, but line 1 has 5");
}

TEST_CASE("point file: refuses a CSV field that is not a number, naming the line", "[point-file]") {
    TempFolder folder;
    checkRefused(writeFile(folder, "word.csv", "0,0,0.5\n1,1,abc\n"), "line 2: column 3 is not a number (\"abc\")");
    checkRefused(writeFile(folder, "comma.csv", "0,0,0.5\n1,1,0,5\n"), "line 2: 4 columns");
    checkRefused(writeFile(folder, "empty.csv", "0,0,0.5,\n"), "line 1: column 4 is empty");
    checkRefused(writeFile(folder, "second.csv", "x,y,v\n0,zero,1\n"), "line 2: column 2 is not a number");
    checkRefused(writeFile(folder, "huge.csv", "0,0,1e999\n"), "line 1: column 3 is out of range");
}

TEST_CASE("point file: refuses NaN and infinity in a CSV", "[point-file]") {
    TempFolder folder;
    checkRefused(writeFile(folder, "nan.csv", "0,0,0.5\n0,1,nan\n"), "line 2: a colour value is not finite");
    checkRefused(writeFile(folder, "inf.csv", "inf,0,0.5\n"), "line 1: a coordinate is not finite");
    checkRefused(writeFile(folder, "nan_y.csv", "0,NaN,0.5\n"), "a coordinate is not finite");
}

TEST_CASE("point file: refuses CSV values out of range", "[point-file]") {
    TempFolder folder;
    checkRefused(writeFile(folder, "negative.csv", "0,0,0.5\n1,1,-0.25\n"), "line 2: negative colour value -0.25");
    checkRefused(writeFile(folder, "above1.csv", "0,0,0.5\n1,1,1.5\n"), "line 2: colour value 1.5 is above 1");
    checkRefused(writeFile(folder, "above255.csv", "0,0,200\n1,1,256\n"), "line 2: colour value 256 is above 255");
    // A fraction anywhere makes the file [0, 1]: the 200 is then out of range, and the
    // message says which line decided that.
    checkRefused(writeFile(folder, "mixed.csv", "0,0,200\n1,1,0.5\n"), "line 1: colour value 200 is above 1");
    checkRefused(writeFile(folder, "mixed2.csv", "0,0,200\n1,1,0.5\n"), "line 2 has 0.5");
}

TEST_CASE("point file: refuses negative CSV coordinates", "[point-file]") {
    TempFolder folder;
    checkRefused(writeFile(folder, "x.csv", "0,0,0.5\n-1,0,0.5\n"), "line 2: negative coordinate x = -1");
    checkRefused(writeFile(folder, "y.csv", "0,-0.5,0.5\n"), "line 1: negative coordinate y = -0.5");
}

// ---- refusals: PLY ----

namespace {

const std::string kRgbVertex = "property float x\nproperty float y\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n";

std::string asciiPly(const std::string& header_body, const std::string& data) {
    return "ply\nformat ascii 1.0\n" + header_body + "end_header\n" + data;
}

}  // namespace

TEST_CASE("point file: refuses a bad PLY header", "[point-file]") {
    TempFolder folder;
    checkRefused(writeFile(folder, "csv.ply", "0,0,1\n"), "not a PLY file");
    checkRefused(writeFile(folder, "format.ply", "ply\nformat binary_middle_endian 1.0\nelement vertex 1\n" + kRgbVertex + "end_header\n"),
                 "bad PLY header: line 2: unknown format");
    checkRefused(writeFile(folder, "noformat.ply", "ply\nelement vertex 1\n" + kRgbVertex + "end_header\n0 0 0 0 0\n"),
                 "bad PLY header: it has no format line");
    checkRefused(writeFile(folder, "noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\n" + kRgbVertex),
                 "bad PLY header: it has no end_header line");
    checkRefused(writeFile(folder, "keyword.ply", asciiPly("element vertex 1\n" + kRgbVertex + "colour 3\n", "")),
                 "bad PLY header: line 9: unknown keyword \"colour\"");
    checkRefused(writeFile(folder, "count.ply", asciiPly("element vertex many\n" + kRgbVertex, "")),
                 "bad PLY header: line 3: the element count \"many\" is not a whole number");
    checkRefused(writeFile(folder, "orphan.ply", asciiPly("property float x\nelement vertex 1\n" + kRgbVertex, "")),
                 "a property before any element");
}

TEST_CASE("point file: refuses unsupported PLY property types", "[point-file]") {
    TempFolder folder;
    checkRefused(writeFile(folder, "unknown.ply", asciiPly("element vertex 1\nproperty quad x\n", "")),
                 "unknown property type \"quad\"");
    checkRefused(writeFile(folder, "intx.ply",
                           asciiPly("element vertex 1\nproperty int x\nproperty int y\nproperty uchar red\n"
                                    "property uchar green\nproperty uchar blue\n",
                                    "0 0 0 0 0\n")),
                 "the vertex property x is int (x and y must be float or double)");
    checkRefused(writeFile(folder, "intred.ply",
                           asciiPly("element vertex 1\nproperty float x\nproperty float y\nproperty int red\n"
                                    "property int green\nproperty int blue\n",
                                    "0 0 0 0 0\n")),
                 "the colour properties are int");
    checkRefused(writeFile(folder, "mixedcolour.ply", asciiPly("element vertex 1\n" + kRgbVertex + "property float alpha\n", "0 0 0 0 0 1\n")),
                 "the colour properties have different types (uchar and float)");
    checkRefused(writeFile(folder, "floatlength.ply",
                           asciiPly("element face 1\nproperty list float int vertex_indices\nelement vertex 1\n" + kRgbVertex, "")),
                 "a list's length must have an integer type");
}

TEST_CASE("point file: refuses a PLY without vertex positions or colours", "[point-file]") {
    TempFolder folder;
    checkRefused(writeFile(folder, "novertex.ply", asciiPly("element face 0\nproperty list uchar int vertex_indices\n", "")),
                 "no vertex element");
    checkRefused(writeFile(folder, "nocolour.ply",
                           asciiPly("element vertex 1\nproperty float x\nproperty float y\nproperty float z\n", "0 0 0\n")),
                 "no vertex colours");
    checkRefused(writeFile(folder, "noblue.ply",
                           asciiPly("element vertex 1\nproperty float x\nproperty float y\nproperty uchar red\n"
                                    "property uchar green\nproperty uchar alpha\n",
                                    "0 0 0 0 0\n")),
                 "no vertex colours");
    checkRefused(writeFile(folder, "noy.ply",
                           asciiPly("element vertex 1\nproperty float x\nproperty uchar red\nproperty uchar green\n"
                                    "property uchar blue\n",
                                    "0 0 0 0\n")),
                 "no vertex positions (properties x and y)");
    checkRefused(writeFile(folder, "twice.ply", asciiPly("element vertex 1\n" + kRgbVertex + "property uchar red\n", "")),
                 "the vertex property red appears twice");
    checkRefused(writeFile(folder, "empty.ply", asciiPly("element vertex 0\n" + kRgbVertex, "")), "no points");
}

TEST_CASE("point file: refuses a list property in the vertex element", "[point-file]") {
    TempFolder folder;
    checkRefused(writeFile(folder, "list.ply", asciiPly("element vertex 1\n" + kRgbVertex + "property list uchar int faces\n", "")),
                 "the vertex element has a list property (faces)");
}

TEST_CASE("point file: refuses a PLY of more than 2^28 points before reading them", "[point-file]") {
    TempFolder folder;
    checkRefused(writeFile(folder, "many.ply", asciiPly("element vertex 268435457\n" + kRgbVertex, "0 0 0 0 0\n")),
                 "268435457 points, more than 268435456");
    // One fewer is allowed by the cap, and then found truncated, without allocating it all.
    checkRefused(writeFile(folder, "cap.ply", asciiPly("element vertex 268435456\n" + kRgbVertex, "0 0 0 0 0\n")),
                 "truncated: the data ends within vertex 1 of the 268435456 the header declares");
}

TEST_CASE("point file: refuses a truncated binary PLY", "[point-file]") {
    TempFolder folder;
    const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\n" + kRgbVertex + "end_header\n";
    Bytes data;
    data(1.0f)(2.0f)(uint8_t(1))(uint8_t(2))(uint8_t(3));
    data(3.0f)(4.0f)(uint8_t(1));  // vertex 1 stops after its red
    checkRefused(writeFile(folder, "cut.ply", header + data.bytes), "truncated: the data ends within vertex 1 of the 3");

    // In an element before the vertices: a list that claims more than the file holds.
    Bytes lists;
    lists(uint8_t(200))(int32_t(0));
    checkRefused(writeFile(folder, "cutlist.ply",
                           "ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list uchar int vertex_indices\n"
                           "element vertex 1\n" + kRgbVertex + "end_header\n" + lists.bytes),
                 "truncated: the data ends within face 0 of the 1");
    // A fixed-size element before the vertices, longer than the file.
    checkRefused(writeFile(folder, "cutfixed.ply",
                           "ply\nformat binary_little_endian 1.0\nelement camera 1000\nproperty double f\n"
                           "element vertex 1\n" + kRgbVertex + "end_header\n" + std::string(80, '\0')),
                 "truncated: the data ends within camera 10 of the 1000");
    // Ascii too.
    checkRefused(writeFile(folder, "cut_ascii.ply", asciiPly("element vertex 2\n" + kRgbVertex, "0 0 1 2 3\n5 5 1\n")),
                 "truncated: the data ends within vertex 1 of the 2");
}

TEST_CASE("point file: refuses a negative list length before the vertices", "[point-file]") {
    TempFolder folder;
    checkRefused(writeFile(folder, "negative.ply",
                           asciiPly("element face 1\nproperty list char int vertex_indices\nelement vertex 1\n" + kRgbVertex,
                                    "-1\n0 0 0 0 0\n")),
                 "face 0 (counting from 0): property vertex_indices has a negative list length");
}

TEST_CASE("point file: refuses NaN, infinity and out-of-range values in a PLY", "[point-file]") {
    TempFolder folder;
    const std::string float_vertex = "element vertex 2\nproperty float x\nproperty float y\nproperty float red\n"
                                     "property float green\nproperty float blue\n";
    Bytes nan;
    nan(0.0f)(0.0f)(0.0f)(0.0f)(0.0f);
    nan(std::numeric_limits<float>::quiet_NaN())(1.0f)(0.0f)(0.0f)(0.0f);
    checkRefused(writeFile(folder, "nan.ply", "ply\nformat binary_little_endian 1.0\n" + float_vertex + "end_header\n" + nan.bytes),
                 "vertex 1 (counting from 0): a coordinate is not finite");
    Bytes inf;
    inf(0.0f)(0.0f)(0.0f)(std::numeric_limits<float>::infinity())(0.0f);
    inf(0.0f)(0.0f)(0.0f)(0.0f)(0.0f);
    checkRefused(writeFile(folder, "inf.ply", "ply\nformat binary_little_endian 1.0\n" + float_vertex + "end_header\n" + inf.bytes),
                 "vertex 0 (counting from 0): a colour value is not finite");
    checkRefused(writeFile(folder, "above.ply", asciiPly(float_vertex, "0 0 0 0 0\n1 1 0.5 1.25 0\n")),
                 "vertex 1 (counting from 0): colour value 1.25 is above 1");
    checkRefused(writeFile(folder, "negative.ply", asciiPly(float_vertex, "0 0 0 -0.5 0\n1 1 0 0 0\n")),
                 "vertex 0 (counting from 0): negative colour value -0.5");
    checkRefused(writeFile(folder, "negx.ply", asciiPly(float_vertex, "0 0 0 0 0\n1 -2 0 0 0\n")),
                 "vertex 1 (counting from 0): negative coordinate y = -2");
    checkRefused(writeFile(folder, "nan_ascii.ply", asciiPly(float_vertex, "nan 0 0 0 0\n1 1 0 0 0\n")),
                 "vertex 0 (counting from 0): a coordinate is not finite");
    checkRefused(writeFile(folder, "uchar.ply", asciiPly("element vertex 1\n" + kRgbVertex, "0 0 300 0 0\n")),
                 "vertex 0 (counting from 0): property red: \"300\" is not a uchar");
    checkRefused(writeFile(folder, "word.ply", asciiPly("element vertex 1\n" + kRgbVertex, "0 zero 0 0 0\n")),
                 "vertex 0 (counting from 0): property y: \"zero\" is not a float");
}
