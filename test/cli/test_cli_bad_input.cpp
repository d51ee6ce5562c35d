// The bad-input catalogue of issue #6, through the real executable: for each, exactly one line
// on stderr naming the file and the reason, the documented exit code, and no file left behind.
// Covered in test_cli_errors.cpp and not repeated here: a missing file, a non-image, truncated
// PNG / JPEG / TIFF / EXR files, 1×1 and 2×1 images, scales 0, negative, NaN and 1e12, an
// output in a missing or read-only folder, and an output that is the input.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <thread>

#include "image_file.h"
#include "png_bytes.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;

void writeBytes(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

// The formats ddtup reads and writes, as its messages list them (core/image_formats.h).
const std::string kFormats = "PNG, JPEG, TIFF, OpenEXR, WebP, BMP, GIF, Targa, PNM, Radiance HDR";

// An input folder and an output folder: the output folder must stay empty after a failure.
struct Workspace {
    TempFolder inputs;
    TempFolder outputs;
    std::string out = outputs / "out.png";

    Run upscale(const std::string& input, const std::vector<std::string>& more = {},
                const std::vector<std::string>& environment = {}) {
        std::vector<std::string> args = {input, "-s", "2", out};
        args.insert(args.end(), more.begin(), more.end());
        return runDdtup(args, environment);
    }
};

// Writes an image with OIIO directly, for channel layouts ddtup itself never writes.
void writeChannels(const std::string& path, int channels, OIIO::TypeDesc type) {
    auto output = OIIO::ImageOutput::create(path);
    REQUIRE(output);
    const OIIO::ImageSpec spec(4, 4, channels, type);
    std::vector<float> pixels(size_t(4 * 4 * channels), 0.25f);
    REQUIRE(output->open(path, spec));
    REQUIRE(output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    REQUIRE(output->close());
}

// A 3-channel noise image: large ones keep ddtup busy for seconds.
ddt::Image noiseImage(uint32_t width, uint32_t height) {
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    ddt::Image image;
    image.width = width;
    image.height = height;
    image.channels = 3;
    image.pixels.resize(size_t(width) * height * 3);
    for (float& sample : image.pixels) sample = float(std::lround(value(rng) * 255.0f)) / 255.0f;
    return image;
}

// Waits until `folder` holds something (a temporary file), at most a minute.
bool waitForAFile(const TempFolder& folder) {
    for (int i = 0; i < 600; ++i) {
        if (!folder.names().empty()) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return false;
}

// Whether this machine lets an unprivileged test mount a file system of its own (user and
// mount namespaces: many containers and CI runners forbid them).
bool canMountTmpfs() { return std::system("unshare -rm sh -c 'mount -t tmpfs -o size=64k tmpfs /tmp' >/dev/null 2>&1") == 0; }

}  // namespace

TEST_CASE("bad input: a folder given as the input file", "[threads]") {
    Workspace work;
    fs::create_directory(work.inputs / "photos.png");
    requireExactError(work.upscale(work.inputs / "photos.png"), 1, work.inputs / "photos.png" + ": is a folder, not an image file");
    CHECK(work.outputs.names().empty());
}

TEST_CASE("bad input: a PNG with bytes flipped in its image data", "[threads]") {
    Workspace work;
    const std::string good = readFile(ddt::test::testDataPath("crop32_astronaut.png"));
    const size_t data = ddt::test::pngChunkData(good, "IDAT");
    REQUIRE(data != std::string::npos);
    const size_t length = size_t(uint8_t(good[data - 6])) << 8 | uint8_t(good[data - 5]);  // under 64 KiB here
    struct Damage {
        const char* name;
        size_t offset;  // into the image data
        size_t bytes;   // how many are inverted
        bool forge_crc; // whether the chunk's CRC is recomputed, so only the zlib checks remain
    };
    const Damage damages[] = {
        {"burst.png", length / 2, 20, false},  {"bit_early.png", 10, 1, false},
        {"bit_middle.png", length / 3, 1, false}, {"bit_late.png", length - 40, 1, false},
        {"forged_crc.png", length / 2, 1, true},
    };
    for (const Damage& damage : damages) {
        INFO(damage.name);
        std::string png = good;
        for (size_t i = 0; i < damage.bytes; ++i) png[data + damage.offset + i] = char(~png[data + damage.offset + i]);
        if (damage.forge_crc) ddt::test::fixPngChunkCrc(png, data);
        writeBytes(work.inputs / damage.name, png);
        requireOneLineError(work.upscale(work.inputs / damage.name), 1, damage.name, ": truncated or corrupt image (");
        CHECK(work.outputs.names().empty());
    }
}

TEST_CASE("bad input: a zero-byte file", "[threads]") {
    Workspace work;
    writeBytes(work.inputs / "empty.png", "");
    requireExactError(work.upscale(work.inputs / "empty.png"), 1, work.inputs / "empty.png" + ": empty file (0 bytes)");
    CHECK(work.outputs.names().empty());
}

TEST_CASE("bad input: 0×0 and 1×N images", "[threads]") {
    Workspace work;
    // libpng refuses a 0×0 header itself ("Invalid IHDR data").
    writeBytes(work.inputs / "zero.png", ddt::test::pngClaiming(0, 0));
    requireExactError(work.upscale(work.inputs / "zero.png"), 1,
                      work.inputs / "zero.png" + ": not a readable PNG image (PNG read error: Invalid IHDR data)");
    ddt::writeImage(work.inputs / "column.png", noiseImage(1, 7));
    requireExactError(work.upscale(work.inputs / "column.png"), 1, work.inputs / "column.png" + ": DDT needs at least 2×2 pixels (got 1×7)");
    CHECK(work.outputs.names().empty());
}

TEST_CASE("bad input: a header claiming 100000×100000 pixels is refused before allocating", "[threads]") {
    Workspace work;
    writeBytes(work.inputs / "huge.png", ddt::test::pngClaiming(100000, 100000));
    requireExactError(work.upscale(work.inputs / "huge.png"), 1,
                      work.inputs / "huge.png" + ": image is 100000×100000 pixels; ddtup reads at most 268435456 pixels (16384×16384)");
    CHECK(work.outputs.names().empty());
}

TEST_CASE("bad input: 5-channel TIFF and EXR files", "[threads]") {
    Workspace work;
    writeChannels(work.inputs / "five.tif", 5, OIIO::TypeDesc::UINT8);
    writeChannels(work.inputs / "five.exr", 5, OIIO::TypeDesc::HALF);
    for (const char* name : {"five.tif", "five.exr"}) {
        INFO(name);
        requireExactError(work.upscale(work.inputs / name), 1,
                          work.inputs / name + ": 5 channels (R, G, B, A, channel4); ddtup reads grey, grey+alpha, RGB or RGBA images with alpha last");
    }
    CHECK(work.outputs.names().empty());
}

TEST_CASE("bad input: NaN or infinite samples in a float EXR", "[threads]") {
    Workspace work;
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                      -std::numeric_limits<float>::infinity()}) {
        INFO(bad);
        ddt::Image image = noiseImage(8, 8);
        image.sample_type = ddt::SampleType::Float;
        image.pixels[100] = bad;
        ddt::writeImage(work.inputs / "bad.exr", image);
        requireExactError(work.upscale(work.inputs / "bad.exr"), 1, work.inputs / "bad.exr" + ": contains NaN or infinite values");
        CHECK(work.outputs.names().empty());
    }
}

// The app's limit on output pixels decides the message; here only that it is one line.
TEST_CASE("bad input: an absurd scale is refused with one line", "[threads]") {
    Workspace work;
    // 32 · 1e9 pixels a side: beyond the documented limit of 2^32 output pixels.
    const Run run = runDdtup({ddt::test::testDataPath("crop32_astronaut.png"), "-s", "1e9", work.out});
    requireOneLineError(run, 1, work.out, "ddtup writes at most 4294967296 pixels (4 gigapixels)");
    CHECK(work.outputs.names().empty());
}

// The real thing: a 64 KiB tmpfs in a private mount namespace, where the machine allows one.
TEST_CASE("bad input: the disk fills up while writing (a full tmpfs)", "[threads]") {
    if (!canMountTmpfs()) {
        WARN("unshare -rm cannot mount a tmpfs here; the injected failure below still runs");
        return;
    }
    Workspace work;
    ddt::writeImage(work.inputs / "noise.png", noiseImage(200, 200));  // 400×400 noise: ~480 KB of PNG
    for (const char* name : {"out.png", "out.jpg", "out.tif", "out.exr", "out.bmp", "out.webp"}) {
        INFO(name);
        // Lists the small disk after ddtup, inside the namespace, on stdout.
        const Run run = runShell("unshare -rm sh -c 'mount -t tmpfs -o size=64k tmpfs \"$1\" && \"$2\" \"$3\" -s 2 \"$1/$4\" "
                                 "--backend cpu -q; status=$?; ls -A \"$1\" >&2; exit $status' sh " +
                                 shellQuoted(work.outputs.path().string()) + " \"$DDTUP\" " +
                                 shellQuoted(work.inputs / "noise.png") + " " + name);
        requireExactError(run, 1, work.outputs / name + ": No space left on device");
    }
}

// Injected through the writer's test hook DDTUP_TEST_WRITE_LIMIT (a write past that many bytes
// fails with ENOSPC), so that every machine runs this one.
TEST_CASE("bad input: the disk fills up while writing (injected)", "[threads]") {
    Workspace work;
    const Run run = work.upscale(ddt::test::testDataPath("crop32_astronaut.png"), {"--backend", "cpu", "-q"},
                                 {"DDTUP_TEST_WRITE_LIMIT=1000"});
    requireExactError(run, 1, work.out + ": No space left on device");
    CHECK(work.outputs.names().empty());
}

TEST_CASE("bad input: no Vulkan device for --backend vulkan") {
    Workspace work;
    const Run run =
        work.upscale(ddt::test::testDataPath("crop32_astronaut.png"), {"--backend", "vulkan"}, kNoVulkanDevice);
    requireOneLineError(run, 3, "Vulkan", "--backend cpu");
    CHECK(work.outputs.names().empty());
}

TEST_CASE("bad input: standard input that is not an image", "[threads]") {
    Workspace work;
    writeBytes(work.inputs / "text", "not an image\n");
    requireExactError(runDdtup({"-", "-s", "2", work.out}, {}, work.inputs / "text"), 1,
                      "standard input: not an image in a format ddtup reads (" + kFormats + ")");
    requireExactError(runDdtup({"-", "-s", "2", work.out}, {}, "/dev/null"), 1, "standard input: empty file (0 bytes)");
    CHECK(work.outputs.names().empty());
}

TEST_CASE("cli: an image on standard input is recognised by its content", "[threads]") {
    Workspace work;
    const Run run = runDdtup({"-", "-s", "2", work.out, "-q", "--backend", "cpu"}, {},
                             ddt::test::testDataPath("crop32_astronaut.png"));
    CHECK(run.exit_code == 0);
    CHECK(run.err.empty());
    CHECK(ddt::ImageReader(work.out).header().width == 64);
}

// 1500×1500 noise at -s 4 keeps the CPU backend busy for many seconds; the writer's
// temporary file appears in the output folder before the input is decoded.
TEST_CASE("cli: SIGINT and SIGTERM remove the temporary output and end by the signal", "[threads]") {
    Workspace work;
    ddt::writeImage(work.inputs / "noise.png", noiseImage(1500, 1500));
    for (int number : {SIGINT, SIGTERM}) {
        INFO("signal " << number);
        BackgroundDdtup ddtup({work.inputs / "noise.png", "-s", "4", work.out, "--backend", "cpu", "-q"});
        REQUIRE(waitForAFile(work.outputs));
        ddtup.signal(number);
        const Run run = ddtup.wait();
        INFO("stderr: " << run.err);
        CHECK(run.end_signal == number);  // a shell reports 128 + the signal: 130, 143
        CHECK(work.outputs.names().empty());
    }
}

// The copy of standard input is a temporary file too.
TEST_CASE("cli: SIGINT while standard input is copied removes the copy", "[threads]") {
    Workspace work;
    TempFolder temp;
    const std::string fifo = work.inputs / "fifo";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    // Opened for reading and writing, the FIFO does not block ddtup's open; it never ends.
    const int feed = ::open(fifo.c_str(), O_RDWR);
    REQUIRE(feed >= 0);
    const std::string png = readFile(ddt::test::testDataPath("crop32_astronaut.png"));
    REQUIRE(::write(feed, png.data(), png.size() / 2) > 0);
    BackgroundDdtup ddtup({"-", "-s", "2", work.out}, {"TMPDIR=" + temp.path().string()}, fifo);
    REQUIRE(waitForAFile(temp));
    ddtup.signal(SIGINT);
    const Run run = ddtup.wait();
    ::close(feed);
    CHECK(run.end_signal == SIGINT);
    CHECK(temp.names().empty());
    CHECK(work.outputs.names().empty());
}

TEST_CASE("bad input: in a batch every bad file fails alone, with its own line, and the good ones are done", "[threads]") {
    Workspace work;
    const auto in = [&](const std::string& name) { return work.inputs / name; };
    ddt::writeImage(in("good1.png"), noiseImage(8, 8));
    ddt::writeImage(in("good2.png"), noiseImage(9, 7));
    fs::create_directory(in("folder.png"));
    writeBytes(in("text.png"), "not an image");
    const std::string png = readFile(in("good1.png"));
    writeBytes(in("truncated.png"), png.substr(0, png.size() / 2));
    writeBytes(in("empty.png"), "");
    writeBytes(in("zero.png"), ddt::test::pngClaiming(0, 0));
    ddt::writeImage(in("column.png"), noiseImage(1, 7));
    writeBytes(in("huge.png"), ddt::test::pngClaiming(100000, 100000));
    writeChannels(in("five.tif"), 5, OIIO::TypeDesc::UINT8);
    ddt::Image nan_image = noiseImage(8, 8);
    nan_image.sample_type = ddt::SampleType::Float;
    nan_image.pixels[5] = std::numeric_limits<float>::quiet_NaN();
    ddt::writeImage(in("nan.exr"), nan_image);
    const std::vector<std::string> bad = {"missing.png", "folder.png", "text.png", "truncated.png", "empty.png",
                                          "zero.png",    "column.png", "huge.png", "five.tif",      "nan.exr"};

    std::vector<std::string> args = {in("good1.png")};
    for (const std::string& name : bad) args.push_back(in(name));
    args.push_back(in("good2.png"));
    args.insert(args.end(), {"-o", work.outputs.path().string(), "-s", "2", "-q"});
    const Run batch = runDdtup(args);
    INFO("stderr: " << batch.err);
    CHECK(batch.exit_code == 1);
    CHECK(batch.out.empty());
    for (const std::string& name : bad) {
        INFO(name);
        // The same line as when the file is given alone, once as it fails and once in the summary.
        const Run alone = runDdtup({in(name), work.outputs / "alone.png", "-s", "2", "-q"});
        REQUIRE(alone.exit_code == 1);
        REQUIRE(alone.err.rfind("ddtup: ", 0) == 0);
        const std::string reason = alone.err.substr(7);
        CHECK_THAT(batch.err, Catch::Contains("ddtup: " + reason));
        CHECK_THAT(batch.err, Catch::Contains("ddtup: failed: " + reason));
    }
    CHECK_THAT(batch.err, Catch::Contains("ddtup: summary: 2 done, 0 skipped, 10 failed"));
    CHECK(work.outputs.names() == std::set<std::string>{"good1.png", "good2.png"});
    CHECK(ddt::ImageReader(work.outputs / "good2.png").header().width == 18);
}

TEST_CASE("bad input: a format OpenImageIO reads but ddtup does not is refused by its content", "[threads]") {
    Workspace work;
    // SGI and FITS: Debian's OIIO reads and writes both; ddtup hands them to no reader.
    writeChannels(work.inputs / "a.sgi", 3, OIIO::TypeDesc::UINT8);
    writeChannels(work.inputs / "b.fits", 1, OIIO::TypeDesc::FLOAT);
    fs::copy_file(work.inputs / "a.sgi", work.inputs / "sgi-named.png");
    for (const char* name : {"a.sgi", "b.fits", "sgi-named.png"})
        requireExactError(work.upscale(work.inputs / name), 1,
                          work.inputs / name + ": not an image in a format ddtup reads (" + kFormats + ")");
    CHECK(work.outputs.names().empty());
}

TEST_CASE("bad input: a PNG named .tga or .sgi is read as the PNG it is", "[threads]") {
    Workspace work;
    const ddt::Image image = noiseImage(6, 5);
    ddt::writeImage(work.inputs / "real.png", image);
    for (const char* name : {"png-named.tga", "png-named.sgi"}) {
        fs::copy_file(work.inputs / "real.png", work.inputs / name);
        const Run run = work.upscale(work.inputs / name, {"--backend", "cpu"});
        INFO(name << ": " << run.err);
        CHECK(run.exit_code == 0);
        CHECK(ddt::readImage(work.out).width == 12);
        fs::remove(work.out);
    }
}

TEST_CASE("bad input: an output format ddtup does not write is refused before any work", "[threads]") {
    Workspace work;
    ddt::writeImage(work.inputs / "a.png", noiseImage(6, 5));
    requireExactError(runDdtup({work.inputs / "a.png", "-s", "2", work.outputs / "a.sgi"}), 1,
                      work.outputs / "a.sgi" + ": the extension .sgi is not a format ddtup writes (" + kFormats + "; see --format)");
    requireExactError(runDdtup({work.inputs / "a.png", "-s", "2", "-f", "dpx", "-o", work.outputs / ""}), 1,
                      work.outputs / "a.dpx" + ": the extension dpx is not a format ddtup writes (" + kFormats + "; see --format)");
    CHECK(work.outputs.names().empty());
}

TEST_CASE("bad input: a folder walk takes the files with the extensions of ddtup's formats only", "[threads]") {
    Workspace work;
    ddt::writeImage(work.inputs / "a.png", noiseImage(6, 5));
    ddt::writeImage(work.inputs / "b.ppm", noiseImage(5, 4));
    writeChannels(work.inputs / "c.sgi", 3, OIIO::TypeDesc::UINT8);
    const Run run = runDdtup({"-i", work.inputs / "", "-o", work.outputs / "", "-s", "2", "--backend", "cpu"});
    INFO(run.err);
    CHECK(run.exit_code == 0);
    CHECK(work.outputs.names() == std::set<std::string>{"a.png", "b.ppm"});
}
