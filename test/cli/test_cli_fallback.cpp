// --fallback through the real executable: lanczos3 is the consistent surface's default, changes
// the picture and keeps the sample type on either backend, and the combinations it cannot serve are refused with one line and
// nothing written.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "image_file.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

TEST_CASE("cli: the consistent surface falls back to lanczos3 by default, the plain one does not, and none turns it off") {
    TempFolder folder;
    ddt::Image image = ddt::readImage(ddt::test::testDataPath("crop32_astronaut.png"));
    ddt::writeImage(folder / "in8.png", image);
    image.sample_type = ddt::SampleType::UInt16;
    ddt::writeImage(folder / "in16.png", image);
    for (const char* name : {"in8.png", "in16.png"}) {
        const std::string input = folder / name;
        ddt::Image outputs[6];
        const std::vector<std::vector<std::string>> extras = {{},
                                                              {"--fallback", "lanczos3"},
                                                              {"--fallback", "none"},
                                                              {"--reconstruct", "plain"},
                                                              {"--reconstruct", "plain", "--fallback", "none"},
                                                              {"--reconstruct", "plain", "--fallback", "lanczos3"}};
        for (size_t i = 0; i < extras.size(); ++i) {
            const std::string output = folder / ("out" + std::to_string(i) + "-" + name);
            std::vector<std::string> args = {input, output, "-s", "3", "--backend", "cpu", "-q"};
            args.insert(args.end(), extras[i].begin(), extras[i].end());
            const Run run = runDdtup(args);
            INFO(name << " " << i << ": " << run.err);
            REQUIRE(run.exit_code == 0);
            outputs[i] = ddt::readImage(output);
            CHECK(outputs[i].width == 96);
            CHECK(outputs[i].sample_type == ddt::readImage(input).sample_type);
        }
        INFO(name);
        CHECK(outputs[0].pixels == outputs[1].pixels);
        CHECK(outputs[0].pixels != outputs[2].pixels);
        CHECK(outputs[3].pixels == outputs[4].pixels);
        CHECK(outputs[3].pixels != outputs[5].pixels);
    }
}

TEST_CASE("cli: --fallback lanczos3 runs on the Vulkan backend and changes its picture", "[vulkan]") {
    // Against the Vulkan backend's own plain surface: the CPU backend's mesh may differ (its
    // serial flips against the parallel rule's), test/image/test_vulkan_fallback.cpp compares
    // the blend itself with the CPU reference.
    TempFolder folder;
    const std::string input = ddt::test::testDataPath("crop32_astronaut.png");
    ddt::Image outputs[2];
    const char* fallbacks[] = {"none", "lanczos3"};
    for (int i = 0; i < 2; ++i) {
        const std::string output = folder / (std::string("out-") + fallbacks[i] + ".png");
        const Run run = runDdtup({input, output, "-s", "3", "--backend", "vulkan", "--reconstruct", "plain", "-q",
                                  "--fallback", fallbacks[i]});
        INFO(fallbacks[i] << ": " << run.err);
        REQUIRE(run.exit_code == 0);
        outputs[i] = ddt::readImage(output);
        CHECK(outputs[i].width == 96);
    }
    CHECK(outputs[0].pixels != outputs[1].pixels);
}

TEST_CASE("cli: --fallback is refused with one line when unknown or where it cannot apply") {
    TempFolder folder;
    const std::string input = folder / "in.png";
    std::filesystem::copy_file(ddt::test::testDataPath("crop32_astronaut.png"), input);
    const std::string mask = folder / "mask.png";
    std::filesystem::copy_file(ddt::test::testDataPath("crop32_astronaut.png"), mask);
    const auto before = folder.names();
    requireOneLineError(runDdtup({input, folder / "out.png", "--fallback", "bicubic"}), 2, "--fallback", "bicubic");
    requireOneLineError(runDdtup({input, folder / "out.png", "--fallback", "lanczos3", "--simplify", "0.5"}), 2,
                        "--fallback lanczos3", "simplification");
    requireOneLineError(runDdtup({input, folder / "out.png", "--fallback", "lanczos3", "--mask", mask}), 2,
                        "--fallback lanczos3", "mask");
    CHECK(folder.names() == before);
}
