// `ddtup -i DIR --mask-dir MASKS -o OUT` through the real executable: each input takes the
// mask of the same name, the outputs equal one-image --mask runs, inputs without exactly one
// mask fail alone, and the refusals.
#include <catch2/catch.hpp>

#include <filesystem>
#include <tuple>

#include "image_file.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

using namespace ddt;
namespace fs = std::filesystem;

const std::string kSample = test::testDataPath("crop32_astronaut.png");

// A 32 × 32 mask, white (known) where `known(x, y)`; the corners always, so the hull is the image.
template <typename Known>
void writeMask(const std::string& path, Known known) {
    std::vector<float> pixels;
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x)
            pixels.push_back(((x == 0 || x == 31) && (y == 0 || y == 31)) || known(x, y) ? 1.0f : 0.0f);
    writeImage(path, test::makeImage(32, 32, 1, pixels));
}

}  // namespace

TEST_CASE("cli mask-dir: each input of a folder tree takes its namesake mask, as --mask would", "[delaunay]") {
    TempFolder work;
    const fs::path in = work.path() / "in", masks = work.path() / "masks", out = work.path() / "out";
    fs::create_directories(in / "sub");
    fs::create_directories(masks / "sub");
    fs::copy_file(kSample, in / "a.png");
    fs::copy_file(kSample, in / "sub" / "b.png");
    // Two different masks, one in another format: the name picks the mask, not the extension.
    writeMask((masks / "a.png").string(), [](uint32_t x, uint32_t y) { return (x + y) % 3 == 0; });
    writeMask((masks / "sub" / "b.tif").string(), [](uint32_t x, uint32_t) { return x % 2 == 0; });

    const Run batch = runDdtup({"-i", in.string(), "-r", "--mask-dir", masks.string(), "-o", out.string(), "-s", "2",
                                "--backend", "cpu", "-q"});
    INFO("stderr: " << batch.err);
    REQUIRE(batch.exit_code == 0);
    CHECK(batch.err.empty());
    for (const auto& [input, mask, output] :
         {std::tuple{in / "a.png", masks / "a.png", out / "a.png"},
          std::tuple{in / "sub" / "b.png", masks / "sub" / "b.tif", out / "sub" / "b.png"}}) {
        INFO(input);
        const std::string single = work / "single.png";
        const Run one = runDdtup({input.string(), "--mask", mask.string(), "-s", "2", single, "--backend", "cpu", "-q"});
        REQUIRE(one.exit_code == 0);
        CHECK(readFile(output.string()) == readFile(single));
    }
    // The two masks differ, so the two outputs must too (the same input under each mask).
    CHECK(readFile((out / "a.png").string()) != readFile((out / "sub" / "b.png").string()));

    // --skip-existing leaves a finished output alone, as for images.
    writeText((out / "a.png").string(), "done before");
    const Run again = runDdtup({"-i", in.string(), "-r", "--mask-dir", masks.string(), "-o", out.string(), "-s", "2",
                                "--backend", "cpu", "--skip-existing"});
    CHECK(again.exit_code == 0);
    CHECK_THAT(again.err, Catch::Contains("summary: 0 done, 2 skipped, 0 failed"));
    CHECK(readFile((out / "a.png").string()) == "done before");
}

TEST_CASE("cli mask-dir: an input without exactly one mask fails alone, and masks are never inputs", "[delaunay]") {
    TempFolder work;
    const fs::path in = work.path() / "in", masks = in / "masks", out = work.path() / "out";
    fs::create_directories(masks);
    for (const char* name : {"a.png", "c.png", "d.png"}) fs::copy_file(kSample, in / name);
    writeMask((masks / "a.png").string(), [](uint32_t x, uint32_t) { return x % 2 == 0; });
    writeMask((masks / "d.png").string(), [](uint32_t x, uint32_t) { return x % 2 == 0; });
    writeMask((masks / "d.tif").string(), [](uint32_t x, uint32_t) { return x % 3 == 0; });

    // The masks' folder lies inside the input folder: with -r it must not be magnified too.
    const Run run = runDdtup({"-i", in.string(), "-r", "--mask-dir", masks.string(), "-o", out.string(), "--backend",
                              "cpu", "-q"});
    INFO("stderr: " << run.err);
    CHECK(run.exit_code == 1);
    CHECK_THAT(run.err, Catch::Contains("ddtup: " + (in / "c.png").string() + ": no mask " + (masks / "c").string() + ".*"));
    CHECK_THAT(run.err, Catch::Contains("ddtup: " + (in / "d.png").string() + ": more than one mask matches"));
    CHECK_THAT(run.err, Catch::Contains("summary: 1 done, 0 skipped, 2 failed"));
    CHECK(fs::exists(out / "a.png"));
    CHECK_FALSE(fs::exists(out / "c.png"));
    CHECK_FALSE(fs::exists(out / "d.png"));
    CHECK_FALSE(fs::exists(out / "masks"));
}

TEST_CASE("cli mask-dir: combinations that cannot work are refused in one line", "[delaunay]") {
    TempFolder work;
    const fs::path masks = work.path() / "masks";
    fs::create_directories(masks);
    const std::string input = work / "a.png", out = work / "out";
    fs::copy_file(kSample, input);
    writeMask((masks / "a.png").string(), [](uint32_t x, uint32_t) { return x % 2 == 0; });
    const std::string dir = masks.string();
    requireOneLineError(runDdtup({input, "--mask", (masks / "a.png").string(), "--mask-dir", dir, "-o", out}), 2,
                        "--mask", "one of them");
    requireOneLineError(runDdtup({input, "--mask-dir", dir, "-o", out, "--simplify", "0.5", "--tile", "64"}), 2,
                        "--mask-dir", "--tile");
    requireOneLineError(runDdtup({input, "--mask-dir", dir, "-o", out, "--tile", "64", "--mesh", "ply"}), 2, "--mask-dir",
                        "--tile");
    requireOneLineError(runDdtup({input, "--mask-dir", work / "none", "-o", out}), 1, work / "none",
                        "folder of masks");
    CHECK_FALSE(fs::exists(out + "/a.png"));
}
