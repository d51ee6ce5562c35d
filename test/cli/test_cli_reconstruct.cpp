// --reconstruct through the real executable: both modes on 8-bit, 16-bit and float inputs keep
// the sample type and the exact output size, the modes give different pictures, and an
// unknown mode is refused with one line.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "image_file.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

TEST_CASE("cli: --reconstruct consistent and plain on 8-bit, 16-bit and float inputs, at exact sizes", "[vulkan]") {
    TempFolder folder;
    ddt::Image image = ddt::readImage(ddt::test::testDataPath("crop32_astronaut.png"));
    ddt::writeImage(folder / "in8.png", image);
    image.sample_type = ddt::SampleType::UInt16;
    ddt::writeImage(folder / "in16.png", image);
    image.sample_type = ddt::SampleType::Float;
    ddt::writeImage(folder / "inf.exr", image);

    for (const char* name : {"in8.png", "in16.png", "inf.exr"}) {
        const std::string input = folder / name;
        const ddt::Image source = ddt::readImage(input);
        for (const char* backend : {"cpu", "vulkan"}) {
            ddt::Image outputs[2];
            int i = 0;
            for (const char* mode : {"consistent", "plain"}) {
                const std::string output = folder / (std::string(mode) + "-" + name);
                const Run run = runDdtup({input, output, "--width", "75", "--height", "41", "--backend", backend,
                                          "--reconstruct", mode, "-q"});
                INFO(name << " " << backend << " " << mode << ": " << run.err);
                REQUIRE(run.exit_code == 0);
                outputs[i] = ddt::readImage(output);
                CHECK(outputs[i].width == 75);
                CHECK(outputs[i].height == 41);
                CHECK(outputs[i].sample_type == source.sample_type);
                ++i;
            }
            INFO(name << " " << backend);
            CHECK(outputs[0].pixels != outputs[1].pixels);
        }
    }
}

TEST_CASE("cli: an unknown --reconstruct mode is refused with one line") {
    TempFolder folder;
    const std::string input = folder / "in.png";
    std::filesystem::copy_file(ddt::test::testDataPath("crop32_astronaut.png"), input);
    const auto before = folder.names();
    const Run run = runDdtup({input, folder / "out.png", "--reconstruct", "sharp"});
    requireOneLineError(run, 2, "--reconstruct", "sharp");
    CHECK(folder.names() == before);
}

TEST_CASE("cli: --assume sets the consistent surface's filter: mixed by default for a PNG, each filter its own picture") {
    TempFolder folder;
    const std::string input = ddt::test::testDataPath("crop32_astronaut.png");
    const std::vector<std::string> kernels = {"", "mixed", "footprint", "box", "bicubic", "lanczos3"};
    std::vector<ddt::Image> outputs;
    for (const std::string& kernel : kernels) {
        const std::string output = folder / ("out-" + (kernel.empty() ? "default" : kernel) + ".png");
        std::vector<std::string> args = {input, output, "-s", "3", "--backend", "cpu", "-q"};
        if (!kernel.empty()) args.insert(args.end(), {"--assume", kernel});
        const Run run = runDdtup(args);
        INFO(kernel << ": " << run.err);
        REQUIRE(run.exit_code == 0);
        outputs.push_back(ddt::readImage(output));
    }
    CHECK(outputs[0].pixels == outputs[1].pixels);
    for (size_t a = 1; a < outputs.size(); ++a)
        for (size_t b = a + 1; b < outputs.size(); ++b) {
            INFO(kernels[a] << " against " << kernels[b]);
            CHECK(outputs[a].pixels != outputs[b].pixels);
        }
}

TEST_CASE("cli: by default a JPEG file is assumed to come through the footprint, and --stats says what was assumed") {
    TempFolder folder;
    const ddt::Image image = ddt::readImage(ddt::test::testDataPath("crop32_astronaut.png"));
    ddt::writeImage(folder / "in.jpg", image);
    ddt::writeImage(folder / "in.png", image);
    // The picture, and --stats' line on the reconstruction, for `input` with `assume` ("": the default).
    auto run = [&](const std::string& input, const std::string& assume, std::string& stats) {
        const std::string output = folder / ("out-" + input + "-" + (assume.empty() ? "default" : assume) + ".png");
        std::vector<std::string> args = {folder / input, output, "-s", "3", "--backend", "cpu", "-q", "--stats"};
        if (!assume.empty()) args.insert(args.end(), {"--assume", assume});
        const Run result = runDdtup(args);
        INFO(input << " " << assume << ": " << result.err);
        REQUIRE(result.exit_code == 0);
        const size_t line = result.out.find("time-recon");
        REQUIRE(line != std::string::npos);
        stats = result.out.substr(line, result.out.find('\n', line) - line);
        return ddt::readImage(output);
    };
    std::string stats_default, stats_named;
    CHECK(run("in.jpg", "", stats_default).pixels == run("in.jpg", "footprint", stats_named).pixels);
    CHECK(stats_default.find("assuming footprint") != std::string::npos);
    CHECK(run("in.jpg", "auto", stats_default).pixels != run("in.jpg", "mixed", stats_named).pixels);
    CHECK(stats_named.find("assuming mixed") != std::string::npos);
    CHECK(run("in.png", "", stats_default).pixels == run("in.png", "mixed", stats_named).pixels);
    CHECK(stats_default.find("assuming mixed") != std::string::npos);
    run("in.jpg", "bicubic", stats_named);
    CHECK(stats_named.find("assuming bicubic") != std::string::npos);
}

TEST_CASE("cli: --assume is refused with one line when unknown or where no surface assumes a filter") {
    TempFolder folder;
    const std::string input = folder / "in.png";
    std::filesystem::copy_file(ddt::test::testDataPath("crop32_astronaut.png"), input);
    const auto before = folder.names();
    requireOneLineError(runDdtup({input, folder / "out.png", "--assume", "gaussian"}), 2, "--assume", "gaussian");
    requireOneLineError(runDdtup({input, folder / "out.png", "--assume", "box", "--reconstruct", "plain"}), 2,
                        "--assume box", "--reconstruct plain");
    requireOneLineError(runDdtup({input, folder / "out.png", "--assume", "bicubic", "--simplify", "0.5"}), 2,
                        "--assume bicubic", "simplification");
    CHECK(folder.names() == before);
}
