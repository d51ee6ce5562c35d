// --memory and the CPU backend's limit for jobs that cannot be tiled (a simplification in one
// piece; masks and larger simplifications go in tiles beyond it):
// it comes from the machine (half its memory) or --memory, not from the small working set
// automatic tiles are sized for.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "image_file.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

using namespace ddt;
namespace fs = std::filesystem;

// A side × side RGB image with some structure, and a mask with a hole in its middle.
void writeInputs(const std::string& image_path, const std::string& mask_path, uint32_t side) {
    std::vector<float> pixels, known;
    for (uint32_t y = 0; y < side; ++y)
        for (uint32_t x = 0; x < side; ++x) {
            for (int c = 0; c < 3; ++c) pixels.push_back(0.5f + 0.4f * float(std::sin(0.05 * (x + 2 * c) + 0.03 * y)));
            const bool hole = x > side / 3 && x < side / 2 && y > side / 3 && y < side / 2;
            known.push_back(hole ? 0.0f : 1.0f);
        }
    writeImage(image_path, test::makeImage(side, side, 3, pixels));
    writeImage(mask_path, test::makeImage(side, side, 1, known));
}

}  // namespace

TEST_CASE("cli memory: a mask larger than the tiles' working set runs on the CPU backend", "[cli]") {
    TempFolder work;
    const std::string input = work / "in.png", mask = work / "mask.png", out = work / "out.png";
    // 900² RGB: about 170 MB by the CPU backend's estimate, above the 160 MiB that automatic
    // tiles are sized for (and that refused this job before masks were tiled too).
    writeInputs(input, mask, 900);
    const Run run = runDdtup({input, "--mask", mask, "-s", "1", out, "--backend", "cpu", "-q"});
    INFO("stderr: " << run.err);
    CHECK(run.exit_code == 0);
    const ImageReader result(out);
    CHECK(result.header().width == 900);
    CHECK(result.header().height == 900);
}

TEST_CASE("cli memory: --memory caps what a job in one piece may hold, and bad sizes are refused", "[cli]") {
    TempFolder work;
    const std::string input = work / "in.png", mask = work / "mask.png", out = work / "out.png";
    // 400² RGB, ×2: about 32 MiB for the mesh and 7 MiB for the output, over 16M's 14 MiB (7/8 of
    // it) and under 64M's 56: a mask goes in tiles, as a simplification does (below).
    writeInputs(input, mask, 400);
    const Run tiled = runDdtup({input, "--mask", mask, out, "--backend", "cpu", "--memory", "16M"});
    CHECK(tiled.exit_code == 0);
    CHECK_THAT(tiled.err, Catch::Contains("tiles"));
    const ImageReader result(out);
    CHECK(result.header().width == 800);
    CHECK(result.header().height == 800);

    // Simplification holds about 0.8 kB per pixel beside the mesh (greedy_simplify.h): 400² RGB
    // needs about 162 MiB in one piece, under 256M's 224; over 64M's 56 MiB it goes in
    // 128-pixel tiles (two at a time, about 18 MiB each), within 16M's 14 MiB in 64-pixel ones
    // (4.5 MiB each). Refused only where even those do not fit: four at a time (--threads 4).
    fs::remove(out);
    requireOneLineError(runDdtup({input, "--simplify", "0.5", out, "--backend", "cpu", "--memory", "16M", "--threads", "4",
                                  "-q"}),
                        1, input, "more than the 14 MiB");
    CHECK_FALSE(fs::exists(out));
    for (const char* memory : {"16M", "64M", "256M"}) {
        INFO("--memory " << memory);
        fs::remove(out);
        CHECK(runDdtup({input, "--simplify", "0.5", out, "--backend", "cpu", "--memory", memory, "-q"}).exit_code == 0);
        CHECK(ImageReader(out).header().width == 800);
    }

    for (const char* bad : {"12Q", "1M", "abc", "-5G", "2GG"})
        requireOneLineError(runDdtup({input, out, "--memory", bad}), 2, std::string("--memory ") + bad, "512M or 4G");
}
