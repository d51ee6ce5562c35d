// Batches through the real executable: several inputs into a folder, folder to folder with
// and without -r, output formats and name clashes, --skip-existing, a bad file in the middle,
// and the usage errors of the batch forms.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>

#include "image_file.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;

const std::string kSample = ddt::test::testDataPath("crop32_astronaut.png");  // 32×32 RGB

// Every file under `folder`, relative, hidden ones included (temporary files start with a dot).
std::set<std::string> filesUnder(const fs::path& folder) {
    std::set<std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(folder))
        if (entry.is_regular_file()) files.insert(fs::relative(entry.path(), folder).string());
    return files;
}

void requireImage(const std::string& path, uint32_t width, uint32_t height) {
    INFO(path);
    REQUIRE(fs::exists(path));
    const ddt::ImageReader reader(path);
    CHECK(reader.header().width == width);
    CHECK(reader.header().height == height);
}

size_t countOf(const std::string& text, const std::string& part) {
    size_t count = 0;
    for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
    return count;
}

}  // namespace

TEST_CASE("batch: several inputs into a folder, a bad one reported at the end", "[threads]") {
    TempFolder folder;
    const std::string good1 = folder / "a.png", good2 = folder / "b ü 名前.png", bad = folder / "bad.png";
    fs::copy_file(kSample, good1);
    fs::copy_file(kSample, good2);
    writeText(bad, "not an image");
    const std::string out = folder / "out";
    const Run run = runDdtup({good1, bad, good2, "-o", out, "-s", "2", "-q"});
    INFO("stderr: " << run.err);
    CHECK(run.exit_code == 1);
    // The bad file fails once as it happens, and is listed again in the summary.
    CHECK(countOf(run.err, "bad.png: ") == 2);
    CHECK_THAT(run.err, Catch::Contains("ddtup: summary: 2 done, 0 skipped, 1 failed"));
    CHECK_THAT(run.err, Catch::Contains("ddtup: failed: " + bad + ": "));
    CHECK(filesUnder(out) == std::set<std::string>{"a.png", "b ü 名前.png"});
    requireImage(out + "/a.png", 64, 64);
    requireImage(out + "/b ü 名前.png", 64, 64);
}

TEST_CASE("batch: a last argument that is a folder, or ends in /, is the output folder, as with cp", "[threads]") {
    TempFolder folder;
    const std::string a = folder / "a.png", b = folder / "b.png";
    fs::copy_file(kSample, a);
    fs::copy_file(kSample, b);
    fs::create_directory(folder / "existing");

    const Run one = runDdtup({a, folder / "existing", "-q", "--backend", "cpu"});
    INFO("stderr: " << one.err);
    CHECK(one.exit_code == 0);
    CHECK(filesUnder(folder / "existing") == std::set<std::string>{"a.png"});
    requireImage(folder / "existing/a.png", 64, 64);

    const Run both = runDdtup({a, b, folder / "new" + "/", "-q", "--backend", "cpu"});
    INFO("stderr: " << both.err);
    CHECK(both.exit_code == 0);
    CHECK(filesUnder(folder / "new") == std::set<std::string>{"a.png", "b.png"});

    // The input's own folder would mean writing over the input.
    const Run own = runDdtup({a, folder.path().string(), "-q", "--backend", "cpu"});
    CHECK(own.exit_code == 1);
    CHECK_THAT(own.err, Catch::Contains("output is the input file; refusing to overwrite it"));
}

TEST_CASE("batch: a folder into a folder, -r keeps the sub-folders", "[threads]") {
    TempFolder folder;
    const fs::path in = folder.path() / "in";
    fs::create_directories(in / "sub" / "deeper");
    fs::copy_file(kSample, in / "top.png");
    fs::copy_file(kSample, in / "sub" / "mid.png");
    fs::copy_file(kSample, in / "sub" / "deeper" / "low.tif");
    fs::copy_file(kSample, in / ".hidden.png");        // hidden: passed over
    writeText((in / "notes.txt").string(), "hello");  // not an image extension: passed over

    const Run flat = runDdtup({"-i", in.string(), "-o", folder / "flat", "-q"});
    INFO("stderr: " << flat.err);
    CHECK(flat.exit_code == 0);
    CHECK(flat.err.empty());
    CHECK(filesUnder(folder.path() / "flat") == std::set<std::string>{"top.png"});

    const Run deep = runDdtup({"-i", in.string(), "-o", folder / "deep", "-r", "-q"});
    CHECK(deep.exit_code == 0);
    CHECK(filesUnder(folder.path() / "deep") == std::set<std::string>{"top.png", "sub/mid.png", "sub/deeper/low.tif"});
    requireImage(folder / "deep/sub/deeper/low.tif", 64, 64);
}

TEST_CASE("batch: an output folder inside the input folder is not read back", "[threads]") {
    TempFolder folder;
    fs::copy_file(kSample, folder / "a.png");
    const std::string out = folder / "x2";
    for (int run_number = 0; run_number < 2; ++run_number) {
        const Run run = runDdtup({"-i", folder.path().string(), "-o", out, "-r", "-q"});
        INFO("stderr: " << run.err);
        CHECK(run.exit_code == 0);
    }
    CHECK(filesUnder(folder.path()) == std::set<std::string>{"a.png", "x2/a.png"});
}

TEST_CASE("batch: -f picks the format, and two inputs with one output name are a clash", "[threads]") {
    TempFolder folder;
    fs::copy_file(kSample, folder / "a.png");
    fs::copy_file(kSample, folder / "b.png");
    ddt::Image image = ddt::readImage(kSample);
    ddt::writeImage(folder / "a.tif", image);
    const std::string out = folder / "out";
    const Run run = runDdtup({folder / "a.png", folder / "a.tif", folder / "b.png", "-o", out, "-f", "jpg", "-q"});
    INFO("stderr: " << run.err);
    CHECK(run.exit_code == 1);
    CHECK_THAT(run.err, Catch::Contains("ddtup: " + folder / "a.tif" + ": its output " + out + "/a.jpg is also the output of " +
                                        folder / "a.png"));
    // Each output named stem + the format's extension; never a.png.jpg.
    CHECK(filesUnder(out) == std::set<std::string>{"a.jpg", "b.jpg"});
    CHECK(ddt::ImageReader(out + "/a.jpg").header().channels == 3);
}

TEST_CASE("batch: --skip-existing resumes without touching finished outputs", "[threads]") {
    TempFolder folder;
    const fs::path in = folder.path() / "in";
    fs::create_directory(in);
    for (const char* name : {"a.png", "b.png", "c.png"}) fs::copy_file(kSample, in / name);
    const std::string out = folder / "out";
    fs::create_directory(out);
    fs::copy_file(kSample, out + "/b.png");  // as if done by an earlier run
    const auto old_time = fs::last_write_time(out + "/b.png");

    const Run first = runDdtup({"-i", in.string(), "-o", out, "--skip-existing", "-v"});
    INFO("stderr: " << first.err);
    CHECK(first.exit_code == 0);
    CHECK_THAT(first.err, Catch::Contains("b.png: skipped"));
    CHECK_THAT(first.err, Catch::Contains("summary: 2 done, 1 skipped, 0 failed"));
    CHECK(fs::last_write_time(out + "/b.png") == old_time);
    requireImage(out + "/a.png", 64, 64);

    const Run second = runDdtup({"-i", in.string(), "-o", out, "--skip-existing"});
    CHECK(second.exit_code == 0);
    CHECK_THAT(second.err, Catch::Contains("summary: 0 done, 3 skipped, 0 failed"));
    // Nothing was left to do, so no device was started (the CPU-device note would show).
    CHECK_THAT(second.err, !Catch::Contains("Vulkan device"));
}

TEST_CASE("batch: an output folder equal to the input folder refuses every image", "[threads]") {
    TempFolder folder;
    fs::copy_file(kSample, folder / "a.png");
    const std::string before = readFile(folder / "a.png");
    const Run run = runDdtup({"-i", folder.path().string(), "-o", folder.path().string(), "-q"});
    INFO("stderr: " << run.err);
    CHECK(run.exit_code == 1);
    CHECK_THAT(run.err, Catch::Contains("a.png: output is the input file; refusing to overwrite it"));
    CHECK(readFile(folder / "a.png") == before);
    CHECK(folder.names() == std::set<std::string>{"a.png"});
}

TEST_CASE("batch: the device is started once for the whole batch", "[vulkan]") {
    TempFolder folder;
    std::vector<std::string> args;
    for (const char* name : {"a.png", "b.png", "c.png", "d.png"}) {
        fs::copy_file(kSample, folder / name);
        args.push_back(folder / name);
    }
    args.insert(args.end(), {"-o", folder / "out", "-v", "--backend", "vulkan"});
    const Run run = runDdtup(args);
    INFO("stderr: " << run.err);
    CHECK(run.exit_code == 0);
    CHECK(countOf(run.err, "a CPU Vulkan device") == 1);
    CHECK(countOf(run.err, " -> ") == 4);  // -v: one line per image
}

TEST_CASE("batch: the batch forms' usage errors", "[threads]") {
    TempFolder folder;
    fs::copy_file(kSample, folder / "a.png");
    const std::string a = folder / "a.png";
    struct Case {
        std::vector<std::string> args;
        std::string reason;
    };
    const Case cases[] = {
        {{a, a, a}, "several inputs need a folder to write into"},
        {{a}, "no output given"},
        {{"-i", folder.path().string()}, "-i needs -o DIR"},
        {{"-i", folder.path().string(), "-o", folder / "o", a}, "not both"},
        {{a, folder / "b.png", "-r"}, "-r needs -i DIR"},
        {{a, folder / "b.png", "-q", "-v"}, "either -q or -v"},
        {{a, folder / "b.png", "--progress", "loud"}, "--progress"},
        {{a, folder / "b.png", "--depth", "12"}, "--depth 12"},
        {{a, folder / "b.png", "--quality", "0"}, "--quality"},
        {{"-", a, "x", "-o", folder / "o"}, "standard input"},
    };
    for (const Case& c : cases) {
        INFO("reason: " << c.reason);
        requireOneLineError(runDdtup(c.args), 2, "ddtup: ", c.reason);
    }
    CHECK(folder.names() == std::set<std::string>{"a.png"});
}

TEST_CASE("batch: a missing input folder is one error", "[threads]") {
    TempFolder folder;
    const Run run = runDdtup({"-i", folder / "nope", "-o", folder / "out"});
    requireOneLineError(run, 1, folder / "nope", "no such folder");
}
