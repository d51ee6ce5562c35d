// --fallback through the real executable: lanczos3 changes the picture and keeps the sample
// type, --backend auto takes the CPU backend and says why, and the combinations it cannot
// serve are refused with one line and nothing written.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "image_file.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

TEST_CASE("cli: --fallback lanczos3 blends the default surface, and none is the default bit for bit") {
    TempFolder folder;
    ddt::Image image = ddt::readImage(ddt::test::testDataPath("crop32_astronaut.png"));
    ddt::writeImage(folder / "in8.png", image);
    image.sample_type = ddt::SampleType::UInt16;
    ddt::writeImage(folder / "in16.png", image);
    for (const char* name : {"in8.png", "in16.png"}) {
        const std::string input = folder / name;
        ddt::Image outputs[3];
        const std::vector<std::vector<std::string>> extras = {{}, {"--fallback", "none"}, {"--fallback", "lanczos3"}};
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
    }
}

TEST_CASE("cli: --fallback under --backend auto runs on the CPU backend and the note says so") {
    TempFolder folder;
    const Run run = runDdtup({ddt::test::testDataPath("crop32_astronaut.png"), folder / "out.png", "-s", "2",
                              "--fallback", "lanczos3"});
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    CHECK(run.err.find("CPU backend") != std::string::npos);
    CHECK(run.err.find("--fallback lanczos3") != std::string::npos);
}

TEST_CASE("cli: --fallback is refused with one line when unknown or where it cannot apply") {
    TempFolder folder;
    const std::string input = folder / "in.png";
    std::filesystem::copy_file(ddt::test::testDataPath("crop32_astronaut.png"), input);
    const std::string mask = folder / "mask.png";
    std::filesystem::copy_file(ddt::test::testDataPath("crop32_astronaut.png"), mask);
    const auto before = folder.names();
    requireOneLineError(runDdtup({input, folder / "out.png", "--fallback", "bicubic"}), 2, "--fallback", "bicubic");
    requireOneLineError(runDdtup({input, folder / "out.png", "--fallback", "lanczos3", "--backend", "vulkan"}), 2,
                        "--fallback lanczos3", "CPU backend");
    requireOneLineError(runDdtup({input, folder / "out.png", "--fallback", "lanczos3", "--simplify", "0.5"}), 2,
                        "--fallback lanczos3", "simplification");
    requireOneLineError(runDdtup({input, folder / "out.png", "--fallback", "lanczos3", "--mask", mask}), 2,
                        "--fallback lanczos3", "mask");
    CHECK(folder.names() == before);
}
