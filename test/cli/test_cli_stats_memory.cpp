// --stats' memory lines: the process's peak resident size, the largest block it allocated and,
// on Vulkan, the largest device buffer. The largest block is how a whole-image buffer on the
// tiled image path would show.
#include <catch2/catch.hpp>

#include <cmath>
#include <optional>
#include <string>

#include "image_file.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

using namespace ddt;

// A width × height RGB picture with structure everywhere, written as 8-bit PNG.
void writePicture(const std::string& path, uint32_t width, uint32_t height) {
    std::vector<float> pixels;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) pixels.push_back(0.5f + 0.4f * float(std::sin(0.07 * (x + 3 * c) + 0.05 * y)));
    Image image = test::makeImage(width, height, 3, pixels);
    image.sample_type = SampleType::UInt8;
    writeImage(path, image);
}

// The MiB figure of the --stats line starting with `key`, if there is one.
std::optional<double> mebibytesOf(const std::string& stats, const std::string& key) {
    const size_t line = stats.find("\n" + key);
    if (line == std::string::npos) return std::nullopt;
    return std::stod(stats.substr(line + 1 + key.size()));
}

const double kMiB = 1024.0 * 1024.0;

}  // namespace

TEST_CASE("cli stats: the largest block of a tiled job is below the input as floats", "[cli]") {
    TempFolder work;
    const std::string input = work / "in.png", out = work / "out.png";
    const uint32_t width = 2048, height = 512;
    writePicture(input, width, height);
    const Run run = runDdtup({input, out, "-s", "2", "--tile", "256", "--backend", "cpu", "-q", "--stats"});
    INFO("stdout: " << run.out << "\nstderr: " << run.err);
    REQUIRE(run.exit_code == 0);
    const std::optional<double> block = mebibytesOf(run.out, "memory-block"), peak = mebibytesOf(run.out, "memory-peak");
    REQUIRE(peak);
    // The input's 8-bit codes are one block, written in full, so resident too.
    const double codes = double(width) * height * 3 / kMiB;
    CHECK(*peak >= codes);
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
    // The sanitizers' operator new replaces ddtup's, which counts the blocks: no line, rather than a wrong one.
    CHECK_FALSE(block);
#else
    REQUIRE(block);
    CHECK(*block >= codes);
    // Tiles of 256 hold a few MiB each, the output streams in 8 MiB bands: nothing of the whole
    // image as floats (12 MiB in, 48 MiB out), which the tiled path must never make.
    CHECK(*block < double(width) * height * 3 * sizeof(float) / kMiB);
#endif
    CHECK(mebibytesOf(run.out, "device-block") == std::nullopt);  // the CPU backend has no device
}

TEST_CASE("cli stats: on Vulkan the largest device buffer holds at least the mesh's edge records", "[vulkan]") {
    TempFolder work;
    const std::string input = work / "in.png", out = work / "out.png";
    const uint32_t side = 256;
    writePicture(input, side, side);
    const Run run = runDdtup({input, out, "-s", "2", "--backend", "vulkan", "-q", "--stats"});
    INFO("stdout: " << run.out << "\nstderr: " << run.err);
    REQUIRE(run.exit_code == 0);
    const std::optional<double> device = mebibytesOf(run.out, "device-block");
    REQUIRE(device);
    // The grid's 3·w·h − 2w − 2h + 1 edges, each with a 16-byte vertex record in one buffer.
    const double edges = 3.0 * side * side - 4.0 * side + 1;
    CHECK(*device >= 16 * edges / kMiB);
    CHECK(*device < 1024);  // a 256² job: far below a GiB
}
