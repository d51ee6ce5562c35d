// The real executable on bad input: exactly one line on stderr naming the file (or option) and
// the reason, a non-zero exit, and no file left behind. Also exact output sizes and -s 1.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "image_file.h"
#include "run_ddtup.h"
#include "test_support.h"
#include "temp_folder.h"

namespace {

namespace fs = std::filesystem;

// A folder holding a copy of an RGB test image, "in.png".
struct Workspace {
    TempFolder folder;
    std::string input = folder / "in.png";
    Workspace() { fs::copy_file(ddt::test::testDataPath("crop32_astronaut.png"), input); }
};

void requireSameImage(const ddt::Image& a, const ddt::Image& b) {
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    REQUIRE(a.channels == b.channels);
    REQUIRE(a.sample_type == b.sample_type);
    CHECK(a.pixels == b.pixels);
}

ddt::Image makeRgbaWithHalfTransparency() {
    ddt::Image image;
    image.width = 4;
    image.height = 3;
    image.channels = 4;
    for (uint32_t i = 0; i < 12; ++i) {
        const float alpha = float(i % 3 == 0 ? 128 : i % 3 == 1 ? 255 : 0) * (1.0f / 255.0f);
        for (uint32_t c = 0; c < 3; ++c) image.pixels.push_back(float((i * 40 + c * 70) % 256) * (1.0f / 255.0f) * alpha);
        image.pixels.push_back(alpha);
    }
    return image;
}

}  // namespace

TEST_CASE("cli: a missing input is refused with one line") {
    Workspace work;
    const auto before = work.folder.names();
    const Run run = runDdtup({work.folder / "missing.png", work.folder / "out.png"});
    requireOneLineError(run, 1, "missing.png", "no such file");
    CHECK(work.folder.names() == before);
}

TEST_CASE("cli: a text file named .png is refused with one line") {
    Workspace work;
    std::ofstream(work.folder / "text.png") << "not an image\n";
    const auto before = work.folder.names();
    const Run run = runDdtup({work.folder / "text.png", work.folder / "out.png"});
    requireOneLineError(run, 1, "text.png", "not an image in a format ddtup reads");
    CHECK(work.folder.names() == before);
}

TEST_CASE("cli: a truncated PNG is refused with one line and no libpng noise") {
    Workspace work;
    const std::string cut = work.folder / "cut.png";
    fs::copy_file(work.input, cut);
    fs::resize_file(cut, fs::file_size(cut) / 2);
    const auto before = work.folder.names();
    const Run run = runDdtup({cut, work.folder / "out.png"});
    requireOneLineError(run, 1, "cut.png", "truncated");
    CHECK_THAT(run.err, !Catch::Contains("libpng"));
    CHECK(work.folder.names() == before);

    fs::resize_file(cut, 60);  // cut inside the header chunks this time
    requireOneLineError(runDdtup({cut, work.folder / "out.png"}), 1, "cut.png", "");
    CHECK(work.folder.names() == before);
}

TEST_CASE("cli: truncated JPEG, TIFF and EXR files are refused with one line") {
    Workspace work;
    const ddt::Image image = ddt::readImage(work.input);
    for (const char* name : {"cut.jpg", "cut.tif", "cut.exr"}) {
        INFO(name);
        const std::string path = work.folder / name;
        ddt::writeImage(path, image);
        fs::resize_file(path, fs::file_size(path) / 2);
        const auto before = work.folder.names();
        requireOneLineError(runDdtup({path, work.folder / "out.png"}), 1, name, "");
        CHECK(work.folder.names() == before);
    }
}

TEST_CASE("cli: images under 2×2 pixels are refused") {
    Workspace work;
    const auto before = work.folder.names();
    for (const char* name : {"one_1x1_rgb.png", "two_2x1_rgb.png"}) {
        const Run run = runDdtup({ddt::test::testDataPath(name), work.folder / "out.png"});
        requireOneLineError(run, 1, name, "DDT needs at least 2×2 pixels");
    }
    CHECK(work.folder.names() == before);
}

TEST_CASE("cli: an output in a missing folder is refused") {
    Workspace work;
    const auto before = work.folder.names();
    const Run run = runDdtup({work.input, work.folder / "no/such/folder/out.png"});
    requireOneLineError(run, 1, "out.png", "does not exist");
    CHECK(work.folder.names() == before);
}

TEST_CASE("cli: an output in a read-only folder is refused") {
    Workspace work;
    // Permissions do not stop root; sysfs refuses even root.
    const bool root = ::geteuid() == 0;
    if (root && !fs::is_directory("/sys")) {
        WARN("running as root without /sys: no read-only folder to test with");
        return;
    }
    const std::string folder = root ? std::string("/sys") : work.folder / "read-only";
    if (!root) {
        fs::create_directory(folder);
        fs::permissions(folder, fs::perms::owner_read | fs::perms::owner_exec);
    }
    const auto before = work.folder.names();
    const Run run = runDdtup({work.input, folder + "/ddtup-test-out.png"});
    requireOneLineError(run, 1, "ddtup-test-out.png", "cannot write");
    CHECK(work.folder.names() == before);
    CHECK(!fs::exists(folder + "/ddtup-test-out.png"));
    if (!root) CHECK(fs::is_empty(folder));
}

TEST_CASE("cli: the input is never overwritten, however the output is spelled") {
    Workspace work;
    fs::create_directory(work.folder / "sub");
    fs::create_symlink(work.input, work.folder / "link.png");
    const std::string original = readFile(work.input);
    const auto before = work.folder.names();
    for (const std::string& output :
         {work.input, work.folder / "sub/../in.png", work.folder / "./in.png", work.folder / "link.png"}) {
        const Run run = runDdtup({work.input, output});
        requireOneLineError(run, 1, output, "is the input");
    }
    CHECK(work.folder.names() == before);
    CHECK(readFile(work.input) == original);
}

TEST_CASE("cli: -s below 1, nan or abc is a usage error") {
    Workspace work;
    const auto before = work.folder.names();
    for (const char* scale : {"0.5", "0", "-2", "nan", "inf", "abc"}) {
        INFO("-s " << scale);
        const Run run = runDdtup({work.input, work.folder / "out.png", "-s", scale});
        requireOneLineError(run, 2, "--scale", scale);
    }
    CHECK(work.folder.names() == before);
}

TEST_CASE("cli: an output size the format cannot hold is refused up front") {
    Workspace work;
    const auto before = work.folder.names();
    // 70000 pixels wide: JPEG stops at 65500 (libjpeg would end the process).
    const Run run = runDdtup({work.input, work.folder / "huge.jpg", "--width", "70000", "--height", "32"});
    requireOneLineError(run, 1, "huge.jpg", "65500");
    // Beyond the documented limit of 2^32 output pixels, whatever the format.
    requireOneLineError(runDdtup({work.input, work.folder / "huge.exr", "-s", "2100"}), 1, "huge.exr",
                        "at most 4294967296 pixels");
    // An absurd factor is refused before any size arithmetic can overflow.
    requireOneLineError(runDdtup({work.input, work.folder / "huge.png", "-s", "1e12"}), 1, "huge.png", "at most");
    CHECK(work.folder.names() == before);
}

TEST_CASE("cli: an output with an unknown extension is refused") {
    Workspace work;
    const auto before = work.folder.names();
    requireOneLineError(runDdtup({work.input, work.folder / "out.xyz"}), 1, "out.xyz", "extension");
    CHECK(work.folder.names() == before);
}

TEST_CASE("cli: -s 1 reproduces RGB, grey, 16-bit and RGBA images exactly", "[vulkan]") {
    Workspace work;
    ddt::Image deep = ddt::readImage(work.input);
    deep.sample_type = ddt::SampleType::UInt16;
    ddt::writeImage(work.folder / "deep.png", deep);
    ddt::writeImage(work.folder / "rgba.png", makeRgbaWithHalfTransparency());
    fs::copy_file(ddt::test::testDataPath("step8_gray.png"), work.folder / "grey.png");

    for (const char* name : {"in.png", "grey.png", "deep.png", "rgba.png"}) {
        INFO(name);
        const std::string input = work.folder / name, output = work.folder / (std::string("s1-") + name);
        for (const char* backend : {"vulkan", "cpu"}) {
            INFO(backend);
            const Run run = runDdtup({input, output, "-s", "1", "-q", "--backend", backend});
            CHECK(run.exit_code == 0);
            CHECK(run.err.empty());
            requireSameImage(ddt::readImage(output), ddt::readImage(input));
        }
    }
}

TEST_CASE("cli: output sizes follow -s, --width and --height") {
    TempFolder folder;
    ddt::Image image;
    image.width = 7;
    image.height = 5;
    image.channels = 3;
    image.pixels.resize(7 * 5 * 3);
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i % 7) / 6.0f;
    const std::string input = folder / "in.png", output = folder / "out.png";
    ddt::writeImage(input, image);

    struct Case {
        std::vector<std::string> args;
        uint32_t width, height;
    };
    // round(s·w) × round(s·h), halves away from zero; one side given keeps the aspect.
    const Case cases[] = {
        {{}, 14, 10},                                 // default -s 2
        {{"-s", "2"}, 14, 10},
        {{"-s", "2.5"}, 18, 13},                      // 17.5 and 12.5 round up
        {{"-s", "3"}, 21, 15},
        {{"-s", "8"}, 56, 40},
        {{"--width", "20"}, 20, 14},                  // 20 · 5/7 = 14.29
        {{"--height", "12"}, 17, 12},                 // 12 · 7/5 = 16.8
        {{"--width", "20", "--height", "9"}, 20, 9},  // both: exactly that
    };
    for (const Case& c : cases) {
        std::vector<std::string> args = {input, output};
        args.insert(args.end(), c.args.begin(), c.args.end());
        const Run run = runDdtup(args);
        INFO("args: " << (c.args.empty() ? std::string("(none)") : c.args[0] + " " + c.args[1]) << "; stderr: " << run.err);
        REQUIRE(run.exit_code == 0);
        const ddt::ImageReader written(output);
        CHECK(written.header().width == c.width);
        CHECK(written.header().height == c.height);
    }
}

TEST_CASE("cli: --help shows every default and --version prints the version") {
    const Run help = runDdtup({"--help"});
    CHECK(help.exit_code == 0);
    CHECK(help.err.empty());
    // Each option's help line: "  -s,--scale FLOAT=2   Magnification …". The default shows as
    // "=value" after the type, or as "(default: …)" in the description.
    std::istringstream lines(help.out);
    std::vector<std::string> option_lines;
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("  -", 0) == 0) option_lines.push_back(line);
    for (const std::string option : {"--scale", "--width", "--height", "--backend", "--stats", "--quiet"}) {
        INFO(option);
        auto line = std::find_if(option_lines.begin(), option_lines.end(), [&](const std::string& l) {
            std::string names = ",";
            names.append(l, 2, l.find(' ', 2) - 2).append(",");
            return names.find(std::string(",").append(option).append(",")) != std::string::npos;
        });
        REQUIRE(line != option_lines.end());
        const std::string head = line->substr(0, line->find("  ", 2));  // names, type, default
        CHECK((head.find('=') != std::string::npos || line->find("(default: ") != std::string::npos));
    }
    const Run version = runDdtup({"--version"});
    CHECK(version.exit_code == 0);
    CHECK(version.out == std::string("ddtup ") + DDTUP_VERSION + "\n");
}
