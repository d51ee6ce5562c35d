// OpenImageIO's codecs come in a module loaded only when a file needs one (codec_module.h):
// the dynamic loader's own log (LD_DEBUG=files, on stderr) says which libraries a run loaded.
#include <catch2/catch.hpp>

#include <string>

#include "image_file.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

const std::string kSample = ddt::test::testDataPath("crop32_astronaut.png");  // 32×32 RGB, 8-bit

bool loaded(const Run& run, const std::string& library) { return run.err.find(library) != std::string::npos; }

}  // namespace

TEST_CASE("codec module: OpenImageIO is not loaded by --version or --help", "[cli]") {
    for (const char* option : {"--version", "--help"}) {
        INFO(option);
        const Run run = runDdtup({option}, {"LD_DEBUG=files"});
        REQUIRE(run.exit_code == 0);
        // The log names every library loaded: the C++ runtime at least, so it is on.
        REQUIRE(loaded(run, "libstdc++"));
        CHECK_FALSE(loaded(run, "libOpenImageIO"));
        CHECK_FALSE(loaded(run, "ddtup-oiio.so"));
    }
}

TEST_CASE("codec module: a TIFF loads it and reads as its PNG twin does", "[cli]") {
    TempFolder folder;
    const ddt::Image image = ddt::readImage(kSample);
    const std::string tiff = folder / "in.tif";
    ddt::writeImage(tiff, image);
    const std::string from_tiff = folder / "from_tiff.png", from_png = folder / "from_png.png";
    const Run run = runDdtup({tiff, "-s", "2", from_tiff, "-q"}, {"LD_DEBUG=files"});
    REQUIRE(run.exit_code == 0);
    CHECK(loaded(run, "ddtup-oiio.so"));
    CHECK(loaded(run, "libOpenImageIO"));
    REQUIRE(runDdtup({kSample, "-s", "2", from_png, "-q"}).exit_code == 0);
    const ddt::Image a = ddt::readImage(from_tiff), b = ddt::readImage(from_png);
    CHECK(a.width == 64);
    CHECK(a.height == 64);
    CHECK(a.pixels == b.pixels);
}
