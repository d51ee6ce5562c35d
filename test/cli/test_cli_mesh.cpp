// --mesh through the real executable: files a real reader (assimp) takes with the counts the
// mesh must have, one per image in the batch forms, and the bad values refused in one line.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "image_file.h"
#include "metrics.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

const std::string kInput = ddt::test::testDataPath("crop32_astronaut.png");  // 32 × 32 RGB

// A count `assimp info FILE` reports ("Vertices:", "Faces:"). assimp-utils' `info` imports
// without post-processing, so it neither joins nor splits vertices.
long assimpCount(const std::string& file, const std::string& what) {
    const Run run = runShell("assimp info " + shellQuoted(file));
    REQUIRE(run.exit_code == 0);
    // (Not <regex>: GCC 12's trips -Wmaybe-uninitialized in the sanitizer builds.)
    const size_t at = run.out.find(what + ":");
    REQUIRE(at != std::string::npos);
    return std::stol(run.out.substr(at + what.size() + 1));
}

}  // namespace

TEST_CASE("cli mesh: PLY and OBJ files that assimp reads, with the grid, its ring and their faces") {
    TempFolder work;
    for (const std::string name : {"mesh.ply", "mesh.obj"}) {
        INFO(name);
        const Run run = runDdtup({kInput, "-s", "3", work / "out.png", "--mesh", work / name, "--backend", "cpu", "-q"});
        REQUIRE(run.exit_code == 0);
        CHECK(run.err.empty());
        // 32 × 32 vertices, a copy of each of the 4 × 32 hull vertices, 4 corners; 2 triangles
        // per grid cell, per hull segment and per corner.
        CHECK(assimpCount(work / name, "Vertices") == 32 * 32 + 4 * 32 + 4);
        CHECK(assimpCount(work / name, "Faces") == 2 * 31 * 31 + 8 * 31 + 8);
    }
    CHECK(work.names() == std::set<std::string>{"mesh.obj", "mesh.ply", "out.png"});
}

// A mask's and a point file's meshes: their samples' triangles, no ring (indexed_mesh.h).
TEST_CASE("cli mesh: a mask's and a point file's mesh files hold their samples, as assimp reads them") {
    TempFolder work;
    // Known: the even columns of the 32 × 32 input, 16 × 32 pixels in a 31 × 31 hull.
    std::vector<float> mask(32 * 32, 0.0f);
    for (uint32_t i = 0; i < 32 * 32; ++i) mask[i] = i % 2 == 0 ? 1.0f : 0.0f;
    ddt::writeImage(work / "mask.png", ddt::test::makeImage(32, 32, 1, mask));
    std::ofstream(work / "points.csv") << "0,0,0.1\n9.5,0,0.5\n0,7.25,0.9\n9.5,7.25,0.3\n4,3,0.7\n";
    const std::pair<std::vector<std::string>, long> cases[] = {
        {{kInput, "--mask", work / "mask.png"}, 16 * 32},
        {{work / "points.csv"}, 5},
    };
    for (const auto& [input, vertices] : cases) {
        INFO(input.front());
        for (const std::string name : {"mesh.ply", "mesh.obj"}) {
            INFO(name);
            std::vector<std::string> args = input;
            args.insert(args.end(), {"-s", "2", work / "out.png", "--mesh", work / name, "--backend", "cpu", "-q"});
            const Run run = runDdtup(args);
            REQUIRE(run.exit_code == 0);
            CHECK(assimpCount(work / name, "Vertices") == vertices);
            // A triangulation of v points, b of them on the hull's boundary, has 2v − b − 2
            // triangles. The mask's boundary: the top and bottom rows' 16 pixels and the side
            // columns' 30 between them; the points': the four corners around the centre.
            const long boundary = vertices == 5 ? 4 : 2 * 16 + 2 * 30;
            CHECK(assimpCount(work / name, "Faces") == 2 * vertices - boundary - 2);
        }
    }
}

TEST_CASE("cli mesh: the Vulkan backend's mesh file has the CPU backend's layout", "[vulkan]") {
    // The serial and the parallel flip orders may end in different meshes, so only the layout
    // is compared: same size, same header. (Every file's mesh is checked to tile the image
    // before it is written: core/image/stitched_mesh.h.)
    TempFolder work;
    REQUIRE(runDdtup({kInput, work / "cpu.png", "--mesh", work / "cpu.ply", "--backend", "cpu", "-q"}).exit_code == 0);
    REQUIRE(runDdtup({kInput, work / "gpu.png", "--mesh", work / "gpu.ply", "--backend", "vulkan", "-q"}).exit_code == 0);
    const std::string cpu = readFile(work / "cpu.ply"), gpu = readFile(work / "gpu.ply");
    CHECK(cpu.size() == gpu.size());
    CHECK(cpu.substr(0, cpu.find("end_header")) == gpu.substr(0, gpu.find("end_header")));
}

TEST_CASE("cli mesh: a tiled image's mesh file is the untiled one's") {
    TempFolder work;
    const std::string photo = ddt::test::testDataPath("../../bench/data/real/astronaut.png");
    for (const std::string tile : {"0", "128"})
        REQUIRE(runDdtup({photo, "-s", "1.5", work / ("out" + tile + ".png"), "--mesh", work / ("mesh" + tile + ".ply"),
                          "--tile", tile, "--reconstruct", "plain", "--backend", "cpu", "-q"})
                    .exit_code == 0);
    CHECK(readFile(work / "mesh0.ply") == readFile(work / "mesh128.ply"));
}

TEST_CASE("cli mesh: the SVG renders with rsvg-convert as ddtup renders the same mesh") {
    TempFolder work;
    REQUIRE(runDdtup({kInput, "-s", "4", work / "plain.png", "--reconstruct", "plain", "--mesh", work / "mesh.svg",
                      "--backend", "cpu", "-q"})
                .exit_code == 0);
    REQUIRE(runShell("rsvg-convert " + shellQuoted(work / "mesh.svg") + " -o " + shellQuoted(work / "svg.png")).exit_code == 0);
    const ddt::Image svg = ddt::readImage(work / "svg.png"), plain = ddt::readImage(work / "plain.png");
    REQUIRE(svg.width == plain.width);
    REQUIRE(svg.height == plain.height);
    // rsvg-convert writes RGBA; the reader may keep the alpha (which must be opaque) or not.
    REQUIRE((svg.channels == 3 || svg.channels == 4));
    std::vector<float> rgb;
    for (size_t i = 0; i < svg.pixels.size(); i += svg.channels) {
        if (svg.channels == 4) CHECK(svg.pixels[i + 3] == 1.0f);
        rgb.insert(rgb.end(), svg.pixels.begin() + i, svg.pixels.begin() + i + 3);
    }
    const double psnr = ddt::peakSignalToNoiseRatio(ddt::toBytes(plain), ddt::toBytes(ddt::test::makeImage(svg.width, svg.height, 3, rgb)));
    // Measured 51 dB on a 96² crop (core/io/svg_format.cpp); seams between antialiased paths
    // would bring it near 20 dB.
    CHECK(psnr > 40.0);
}

TEST_CASE("cli mesh: an SVG beyond the size librsvg takes is refused before any work") {
    TempFolder work;
    const std::string photo = ddt::test::testDataPath("../../bench/data/real/astronaut.png");  // 512²: 526 338 triangles
    requireExactError(runDdtup({photo, work / "out.png", "--mesh", work / "mesh.svg", "--backend", "cpu", "-q"}), 1,
                      work / "mesh.svg" + ": the mesh has 526338 triangles, and SVG export takes at most 200000 "
                                          "(librsvg refuses larger documents); write PLY or OBJ");
    CHECK(work.names().empty());
}

TEST_CASE("cli mesh: the batch forms write one mesh beside each output, named like it") {
    TempFolder work;
    const Run run = runDdtup({kInput, ddt::test::testDataPath("diag16_rgb.png"), "-o", work / "out", "--mesh", "OBJ",
                              "--backend", "cpu", "-q"});
    REQUIRE(run.exit_code == 0);
    CHECK(std::filesystem::exists(work / "out/crop32_astronaut.obj"));
    CHECK(std::filesystem::exists(work / "out/diag16_rgb.obj"));
}

TEST_CASE("cli mesh: --simplify keeps the fraction of the vertices asked for, and the file has them") {
    TempFolder work;
    const Run run = runDdtup({kInput, "-s", "2", work / "out.png", "--simplify", "0.25", "--mesh", work / "mesh.ply",
                              "--backend", "cpu", "-q"});
    REQUIRE(run.exit_code == 0);
    CHECK(run.err.empty());
    // 256 of the 1024 vertices, at most a copy of each kept hull vertex and the 4 corners' copies.
    const long vertices = assimpCount(work / "mesh.ply", "Vertices");
    CHECK(vertices > 256 + 4 + 4);
    CHECK(vertices <= 256 + 4 * 32 + 4);
    const ddt::Image out = ddt::readImage(work / "out.png");
    CHECK(out.width == 64);
    CHECK(out.height == 64);
}

TEST_CASE("cli mesh: --stats names the simplifier: the parallel rule on Vulkan, the serial one on the CPU", "[vulkan]") {
    TempFolder work;
    const Run device = runDdtup({kInput, work / "out.png", "--simplify", "0.5", "--backend", "vulkan", "--stats"});
    REQUIRE(device.exit_code == 0);
    CHECK_THAT(device.out, Catch::Contains("vertices       1024 -> 512  (the parallel rule on the device, "));
    CHECK_THAT(device.out, Catch::Contains("(build the mesh, upload, optimize, simplify)"));
    const Run cpu = runDdtup({kInput, work / "out.png", "--simplify", "0.5", "--backend", "cpu", "--stats"});
    REQUIRE(cpu.exit_code == 0);
    CHECK_THAT(cpu.out, Catch::Contains("vertices       1024 -> 512  (the serial greedy simplifier)"));
}

TEST_CASE("cli mesh: on Vulkan, --simplify writes the same mesh and image whatever lavapipe's thread count", "[heavy][vulkan]") {
    TempFolder work;
    std::string meshes[2], images[2];
    int i = 0;
    for (const char* threads : {"1", "3"}) {
        const std::string mesh = work / (std::string("mesh") + threads + ".ply"),
                          image = work / (std::string("out") + threads + ".png");
        REQUIRE(runDdtup({kInput, "-s", "2", image, "--simplify", "0.3", "--mesh", mesh, "--backend", "vulkan", "-q"},
                         {std::string("LP_NUM_THREADS=") + threads})
                    .exit_code == 0);
        meshes[i] = readFile(mesh);
        images[i++] = readFile(image);
    }
    CHECK(!meshes[0].empty());
    CHECK(meshes[0] == meshes[1]);
    CHECK(images[0] == images[1]);
}

TEST_CASE("cli mesh: --max-error simplifies as far as the error allows") {
    TempFolder work;
    long vertices[2];
    int i = 0;
    for (const std::string error : {"2", "8"}) {
        const std::string mesh = work / ("mesh" + error + ".ply");
        REQUIRE(runDdtup({kInput, work / "out.png", "--max-error", error, "--mesh", mesh, "--backend", "cpu", "-q"}).exit_code == 0);
        vertices[i++] = assimpCount(mesh, "Vertices");
    }
    CHECK(vertices[0] < 32 * 32 + 4 * 32 + 4);  // fewer than the full mesh's
    CHECK(vertices[1] < vertices[0]);           // a larger error allows more collapses
}

TEST_CASE("cli mesh: bad --simplify values get one line") {
    TempFolder work;
    const std::string out = work / "out.png";
    for (const std::string value : {"0", "1.5", "-0.1", "nan"})
        requireExactError(runDdtup({kInput, out, "--simplify", value}), 2,
                          "--simplify must be a fraction in (0, 1] (got " + value + ")");
    for (const std::string value : {"0", "-1", "inf"})
        requireExactError(runDdtup({kInput, out, "--max-error", value}), 2,
                          "--max-error must be a positive number of 8-bit levels (got " + value + ")");
    requireExactError(runDdtup({kInput, out, "--simplify", "0.5", "--reconstruct", "consistent"}), 2,
                      "simplification (--simplify, --max-error) renders the linear surface on the simplified mesh; "
                      "--reconstruct consistent does not apply");
    const std::string photo = ddt::test::testDataPath("../../bench/data/real/astronaut.png");
    // --tile now cuts a simplification too (test/simplify/test_tiled_simplify.cpp), but its
    // tiles' meshes are not written yet.
    requireExactError(runDdtup({photo, out, "--simplify", "0.5", "--backend", "cpu", "--tile", "128", "--mesh",
                                work / "mesh.ply", "-q"}),
                      1,
                      photo + ": --mesh does not combine yet with a simplification in tiles (512×512 in 128-pixel "
                              "tiles); in one piece it needs a --memory that holds it and no smaller --tile");
    CHECK(work.names().empty());
}

TEST_CASE("cli mesh: bad --mesh values get one line") {
    TempFolder work;
    const std::string out = work / "out.png";
    requireExactError(runDdtup({kInput, out, "--mesh", work / "mesh.stl"}), 2,
                      "--mesh " + work / "mesh.stl" + ": unknown mesh format (the extension must name ply, obj or svg)");
    requireExactError(runDdtup({kInput, out, "--mesh", kInput}), 2,
                      "--mesh " + kInput + ": unknown mesh format (the extension must name ply, obj or svg)");
    requireExactError(runDdtup({kInput, out, "--mesh-height", "5"}), 2, "--mesh-height needs --mesh");
    // An image may be named anything: OpenImageIO reads by content.
    std::filesystem::copy_file(kInput, work / "in.ply");
    requireExactError(runDdtup({work / "in.ply", out, "--mesh", work / "in.ply"}), 2,
                      "--mesh " + work / "in.ply" + ": is the input; refusing to overwrite it");
    std::filesystem::remove(work / "in.ply");
    requireExactError(runDdtup({kInput, out, "--mesh", out}), 2, "--mesh " + out + ": unknown mesh format (the extension must name ply, obj or svg)");
    requireExactError(runDdtup({kInput, work / "out.ply", "--mesh", work / "out.ply"}), 2,
                      "--mesh " + work / "out.ply" + ": is also the image's output");
    requireExactError(runDdtup({kInput, "-o", work / "dir", "--mesh", work / "m.ply"}), 2,
                      "--mesh " + work / "m.ply" + ": in the batch forms give a format, ply, obj or svg (each mesh goes "
                      "beside its output, named like it)");
    CHECK(work.names().empty());
}

TEST_CASE("cli mesh: an unwritable mesh fails its image, and no file is left") {
    TempFolder work;
    const std::string out = work / "out.png";
    requireExactError(runDdtup({kInput, out, "--mesh", work / "missing/mesh.ply", "--backend", "cpu", "-q"}), 1,
                      work / "missing/mesh.ply" + ": folder " + work / "missing" + " does not exist");
    CHECK(work.names().empty());
    // A full disk, injected through the writers' test hook (core/io/checked_file.h): a file
    // takes at most 20 000 bytes, which the image (8.6 kB) fits and the mesh (46 kB) does not.
    requireExactError(runDdtup({kInput, out, "--mesh", work / "mesh.ply", "--backend", "cpu", "-q"},
                               {"DDTUP_TEST_WRITE_LIMIT=20000"}),
                      1, work / "mesh.ply" + ": No space left on device");
    CHECK(work.names().empty());
}
