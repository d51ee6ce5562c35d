// Standard input and output, the output options (--depth, --quality, -f), and what the
// input file says beyond its pixels (orientation, several images, DPI), through the real
// executable.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <functional>

#include "image_file.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;

const std::string kSample = ddt::test::testDataPath("crop32_astronaut.png");  // 32×32 RGB, 8-bit

}  // namespace

TEST_CASE("streams: an image piped through - in and - out equals the file-to-file result", "[threads]") {
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

TEST_CASE("streams: a full standard output is one error line", "[threads]") {
    const Run run = runShell("\"$DDTUP\" " + shellQuoted(kSample) + " - -f png -q > /dev/full");
    requireExactError(run, 1, "standard output: No space left on device");
}

TEST_CASE("streams: a standard input that cannot be copied is one error line, and leaves no copy", "[threads]") {
    // The copy goes to $TMPDIR; a full disk there is injected (DDTUP_TEST_WRITE_LIMIT): the
    // 100 bytes allowed are fewer than the sample's, so the copy fails before any decoding.
    TempFolder temp;
    const Run run = runDdtup({"-", temp / "out.png", "-q"}, {"TMPDIR=" + temp.path().string(), "DDTUP_TEST_WRITE_LIMIT=100"},
                             kSample);
    requireExactError(run, 1,
                      "standard input: cannot copy it to a temporary file in " + temp.path().string() +
                          " (No space left on device)");
    CHECK(temp.names().empty());
}

TEST_CASE("streams: standard output from standard input needs -f", "[threads]") {
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
    // An ignored --quality gives equal sizes; 10 against 100 gives 1360 against 11668 bytes
    // here, so "half the size" holds with room for other libjpeg versions.
    CHECK(fs::file_size(folder / "low.jpg") * 2 < fs::file_size(folder / "high.jpg"));

    const Run batch = runDdtup({kSample, "-o", folder / "out", "-f", "tif", "-q"});
    CHECK(batch.exit_code == 0);
    CHECK(fs::exists(folder / "out/crop32_astronaut.tif"));
    CHECK(ddt::ImageReader(folder / "out/crop32_astronaut.tif").header().width == 64);
}

namespace {

// A 6×4 RGB image written with OIIO directly, its spec amended by `describe`, in `pages`
// subimages.
void writeRaw(const std::string& path, const std::function<void(OIIO::ImageSpec&)>& describe, int pages = 1) {
    OIIO::ImageSpec spec(6, 4, 3, OIIO::TypeDesc::UINT8);
    describe(spec);
    std::vector<OIIO::ImageSpec> specs(size_t(pages), spec);
    auto output = OIIO::ImageOutput::create(path);
    REQUIRE(output);
    REQUIRE(output->open(path, pages, specs.data()));
    std::vector<uint8_t> pixels(6 * 4 * 3);
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = uint8_t(i * 7);
    for (int page = 0; page < pages; ++page) {
        if (page) REQUIRE(output->open(path, spec, OIIO::ImageOutput::AppendSubimage));
        REQUIRE(output->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    }
    REQUIRE(output->close());
}

OIIO::ImageSpec specOf(const std::string& path) {
    auto input = OIIO::ImageInput::open(path);
    REQUIRE(input);
    return input->spec();
}

}  // namespace

TEST_CASE("files: EXIF orientation, several images in one file and DPI through the executable") {
    TempFolder folder;
    // Orientation 6: the stored 6×4 pixels show rotated a quarter turn, upright 4×6.
    writeRaw(folder / "turned.tif", [](OIIO::ImageSpec& spec) { spec.attribute("Orientation", 6); });
    const Run turned = runDdtup({folder / "turned.tif", folder / "upright.tif", "-s", "2", "-q"});
    REQUIRE(turned.exit_code == 0);
    const OIIO::ImageSpec upright = specOf(folder / "upright.tif");
    CHECK(upright.width == 8);
    CHECK(upright.height == 12);
    CHECK(upright.get_int_attribute("Orientation", 1) == 1);

    writeRaw(folder / "pages.tif", [](OIIO::ImageSpec&) {}, 3);
    const Run pages = runDdtup({folder / "pages.tif", folder / "first.png", "--backend", "cpu"});
    CHECK(pages.exit_code == 0);
    CHECK(pages.err == "ddtup: note: " + folder / "pages.tif" + ": has more than one image (pages or frames); using the first\n");
    CHECK(specOf(folder / "first.png").width == 12);

    writeRaw(folder / "dpi.tif", [](OIIO::ImageSpec& spec) {
        spec.attribute("XResolution", 72.0f);
        spec.attribute("YResolution", 72.0f);
        spec.attribute("ResolutionUnit", "inch");
    });
    REQUIRE(runDdtup({folder / "dpi.tif", folder / "dpi-x3.tif", "-s", "3", "-q"}).exit_code == 0);
    CHECK(specOf(folder / "dpi-x3.tif").get_float_attribute("XResolution") == Approx(216.0f));
}
