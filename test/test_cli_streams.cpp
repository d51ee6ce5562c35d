// Standard input and output, and the output options (--depth, --quality, -f), through the
// real executable.
#include <catch2/catch.hpp>

#include <filesystem>

#include "image.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;

const std::string kSample = ddt::test::testDataPath("crop32_astronaut.png");  // 32×32 RGB, 8-bit

}  // namespace

TEST_CASE("streams: an image piped through - in and - out equals the file-to-file result") {
    TempFolder folder;
    const std::string piped = folder / "piped.png", direct = folder / "direct.png";
    const Run pipe = runShell("\"$DDTUP\" - -s 2 - -f png -q < " + shellQuoted(kSample) + " > " + shellQuoted(piped));
    INFO("stderr: " << pipe.err);
    REQUIRE(pipe.exit_code == 0);
    CHECK(pipe.err.empty());
    REQUIRE(runDdtup({kSample, direct, "-s", "2", "-q"}).exit_code == 0);
    const ddt::Image a = ddt::readImage(piped), b = ddt::readImage(direct);
    CHECK(a.width == 64);
    CHECK(a.height == 64);
    CHECK(a.pixels == b.pixels);
    // Without -f, standard output follows the input's extension.
    const Run follow = runShell("\"$DDTUP\" " + shellQuoted(kSample) + " - -q > " + shellQuoted(folder / "follow.png"));
    CHECK(follow.exit_code == 0);
    CHECK(ddt::readImage(folder / "follow.png").pixels == b.pixels);
}

TEST_CASE("streams: a full standard output is one error line") {
    const Run run = runShell("\"$DDTUP\" " + shellQuoted(kSample) + " - -f png -q > /dev/full");
    requireExactError(run, 1, "standard output: No space left on device");
}

TEST_CASE("streams: standard output from standard input needs -f") {
    const Run run = runDdtup({"-", "-"}, {}, kSample);
    requireOneLineError(run, 2, "standard output", "-f FORMAT");
}

TEST_CASE("output options: --depth, --quality and -f reach the file") {
    TempFolder folder;
    REQUIRE(runDdtup({kSample, folder / "deep.png", "--depth", "16", "-q"}).exit_code == 0);
    CHECK(ddt::ImageReader(folder / "deep.png").header().sample_type == ddt::SampleType::UInt16);
    REQUIRE(runDdtup({kSample, folder / "float.exr", "--depth", "float", "-q"}).exit_code == 0);
    CHECK(ddt::ImageReader(folder / "float.exr").header().sample_type == ddt::SampleType::Float);

    REQUIRE(runDdtup({kSample, folder / "low.jpg", "-s", "4", "--quality", "10", "-q"}).exit_code == 0);
    REQUIRE(runDdtup({kSample, folder / "high.jpg", "-s", "4", "--quality", "100", "-q"}).exit_code == 0);
    CHECK(fs::file_size(folder / "low.jpg") * 2 < fs::file_size(folder / "high.jpg"));

    const Run batch = runDdtup({kSample, "-o", folder / "out", "-f", "tif", "-q"});
    CHECK(batch.exit_code == 0);
    CHECK(fs::exists(folder / "out/crop32_astronaut.tif"));
    CHECK(ddt::ImageReader(folder / "out/crop32_astronaut.tif").header().width == 64);
}
