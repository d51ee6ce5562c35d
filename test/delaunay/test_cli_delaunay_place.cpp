// --delaunay through the real executable: the device's triangulation of a mask's known pixels
// and of a point file's points gives the same output, byte for byte, as the host's; --stats
// says which ran; auto takes the host on a CPU device (lavapipe, the device these tests have).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include "image_file.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

using namespace ddt;

// The end of --stats' time-comp line: where the samples were triangulated.
std::string triangulatedOn(const Run& run) {
    const size_t at = run.out.find("time-comp");
    REQUIRE(at != std::string::npos);
    const std::string line = run.out.substr(at, run.out.find('\n', at) - at);
    const size_t on = line.find("triangulated on the ");
    return on == std::string::npos ? "" : line.substr(on + 20, line.find(')', on) - on - 20);
}

}  // namespace

TEST_CASE("cli delaunay: the device's triangulation gives the host's output, and --stats says where", "[vulkan]") {
    TempFolder work;
    std::mt19937 rng(5);
    const uint32_t w = 64, h = 48;
    writeImage(work / "in.png", test::randomImage(rng, w, h, 3, 256));
    std::vector<float> mask(size_t(w) * h);
    std::bernoulli_distribution known(0.3);
    for (float& value : mask) value = known(rng) ? 1.0f : 0.0f;
    writeImage(work / "mask.png", test::makeImage(w, h, 1, mask));
    {
        std::ofstream points(work / "points.csv");
        std::uniform_real_distribution<double> x(0.0, w - 1.0), y(0.0, h - 1.0), level(0.0, 255.0);
        for (int i = 0; i < 300; ++i) points << x(rng) << "," << y(rng) << "," << int(level(rng)) << "\n";
    }
    const std::vector<std::vector<std::string>> inputs = {
        {work / "in.png", "--mask", work / "mask.png"},
        {work / "points.csv", "--frame", "64x48"},
    };
    for (const std::vector<std::string>& input : inputs) {
        INFO(input.front());
        std::map<std::string, std::string> outputs;
        for (const char* place : {"cpu", "device", "auto"}) {
            INFO(place);
            const std::string out = work / (std::string(place) + ".png");
            std::vector<std::string> args = input;
            args.insert(args.end(), {"-s", "3", out, "--backend", "vulkan", "--delaunay", place, "--stats", "-q"});
            const Run run = runDdtup(args);
            REQUIRE(run.exit_code == 0);
            // auto: lavapipe is a CPU device, where the serial triangulation is the faster.
            CHECK(triangulatedOn(run) == (std::string(place) == "device" ? "Vulkan device" : "CPU"));
            outputs[place] = readFile(out);
        }
        CHECK(outputs["device"] == outputs["cpu"]);
        CHECK(outputs["auto"] == outputs["cpu"]);
        // The CPU backend triangulates on the host, and says so.
        std::vector<std::string> args = input;
        args.insert(args.end(), {"-s", "3", work / "host.png", "--backend", "cpu", "--stats", "-q"});
        const Run run = runDdtup(args);
        REQUIRE(run.exit_code == 0);
        CHECK(triangulatedOn(run) == "CPU");
    }
}

TEST_CASE("cli delaunay: --delaunay is refused in one line where it cannot apply") {
    TempFolder work;
    std::mt19937 rng(6);
    writeImage(work / "in.png", test::randomImage(rng, 16, 12, 3, 256));
    writeImage(work / "mask.png", test::makeImage(16, 12, 1, std::vector<float>(16 * 12, 1.0f)));
    const std::string out = work / "out.png";
    requireOneLineError(runDdtup({work / "in.png", out, "--delaunay", "device"}), 2, "--delaunay",
                        "applies to masks and point files");
    requireOneLineError(runDdtup({work / "in.png", "--mask", work / "mask.png", out, "--delaunay", "device", "--backend", "cpu"}),
                        2, "--delaunay", "--backend cpu uses none");
    requireOneLineError(runDdtup({work / "in.png", "--mask", work / "mask.png", out, "--delaunay", "gpu"}), 2,
                        "--delaunay", "gpu");
    CHECK_FALSE(std::filesystem::exists(out));
}
