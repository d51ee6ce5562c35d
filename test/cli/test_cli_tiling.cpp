// Tiling through the executable: --tile gives the untiled image (seams invisible), progress
// names the tiles, and a device that runs out of memory (injected: DDTUP_TEST_DEVICE_MEMORY,
// since a real out-of-memory cannot be provoked in CI) leads to smaller tiles, never to a
// black or partial image.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <tuple>

#include "flat_json.h"
#include "image_file.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;

// The shared 300×200 photo crop as a file: tiles of 64 meet in every direction.
std::string writePhotoCrop(const TempFolder& folder) {
    const std::string path = folder / "photo.png";
    ddt::writeImage(path, ddt::test::photoCrop());
    return path;
}

ddt::test::Agreement compareFiles(const std::string& a, const std::string& b) {
    const ddt::Image image_a = ddt::readImage(a), image_b = ddt::readImage(b);
    REQUIRE(image_a.width == image_b.width);
    REQUIRE(image_a.height == image_b.height);
    return ddt::test::compareSamples(image_a.pixels, image_b.pixels);
}

}  // namespace

TEST_CASE("tiling cli: --tile 64 gives the untiled image, and progress names the tiles and the time left", "[vulkan]") {
    TempFolder folder;
    const std::string input = writePhotoCrop(folder);
    for (const char* backend : {"vulkan", "cpu"}) {
        INFO(backend);
        const std::string whole = folder / "whole.png", tiled = folder / "tiled.png";
        // A tile side beyond the image makes it one piece (the CPU backend's automatic tiles
        // would cut it for its threads).
        REQUIRE(runDdtup({input, whole, "-s", "2", "-q", "--backend", backend, "--tile", "100000"}).exit_code == 0);
        const Run run = runDdtup({input, tiled, "-s", "2", "--tile", "64", "--progress=json", "--backend", backend});
        REQUIRE(run.exit_code == 0);
        // The bar: within 1/255 on at least 99.9 % of the samples. (Measured with the
        // default overlap of 16: equal, bit for bit; test_tiling.cpp prints the numbers.)
        CHECK(compareFiles(whole, tiled).within_one_level >= 0.999);
        std::set<std::string> tiles_seen;
        for (const auto& event : parseJsonLines(run.err)) {
            if (event.at("event") != "stage") continue;
            // The time left is known from the first finished tile on, and is 0 once all are.
            const double remaining = std::stod(event.at("remaining"));
            if (event.at("stage") == "write") CHECK(remaining == 0.0);
            if (!event.count("tiles")) continue;
            CHECK(event.at("tiles") == "20");  // 5 × 4 tiles of 64 over 300 × 200
            tiles_seen.insert(event.at("tile"));
            if (event.at("tile") == "0") CHECK(remaining == -1.0);
            else CHECK(remaining >= 0.0);
        }
        CHECK(tiles_seen.size() == 20);
    }
}

// On two threads the CPU backend cuts an image beyond kParallelTileSide (256) that would fit
// in one piece into 256-pixel tiles, one per thread at a time, without the note that memory
// asked for them; on one thread it keeps the image whole.
TEST_CASE("tiling cli: the CPU backend on two threads tiles an image beyond 256 pixels that fits, on one keeps it whole") {
    TempFolder folder;
    const std::string input = writePhotoCrop(folder);  // 300 × 200: two tiles of 150 × 200
    const std::string automatic = folder / "automatic.png", tiled = folder / "tiled.png";
    const Run run = runDdtup({input, automatic, "-s", "2", "--threads", "2", "--backend", "cpu", "--progress=json"});
    REQUIRE(run.exit_code == 0);
    std::set<std::string> tiles_seen;
    for (const auto& event : parseJsonLines(run.err)) {
        if (event.at("event") == "notice") CHECK(event.at("message").find("memory") == std::string::npos);
        if (event.at("event") != "stage" || !event.count("tiles")) continue;
        CHECK(event.at("tiles") == "2");
        tiles_seen.insert(event.at("tile"));
    }
    CHECK(tiles_seen.size() == 2);
    REQUIRE(runDdtup({input, tiled, "-s", "2", "-q", "--threads", "2", "--backend", "cpu", "--tile", "256"}).exit_code == 0);
    CHECK(readFile(automatic) == readFile(tiled));

    const std::string one_thread = folder / "one-thread.png", whole = folder / "whole.png";
    const Run single = runDdtup({input, one_thread, "-s", "2", "--threads", "1", "--backend", "cpu", "--progress=json"});
    REQUIRE(single.exit_code == 0);
    for (const auto& event : parseJsonLines(single.err)) CHECK(event.count("tiles") == 0);
    REQUIRE(runDdtup({input, whole, "-s", "2", "-q", "--threads", "1", "--backend", "cpu", "--tile", "100000"}).exit_code == 0);
    CHECK(readFile(one_thread) == readFile(whole));
    // (On this photo 256-pixel tiles give one piece's bytes, as the first test finds for 64:
    // the progress events, not the bytes, tell the two ways apart.)
}

// Automatic tiles come as many a strip as the threads take at once: a 600-pixel-wide image,
// three 200-pixel cores for 256-pixel tiles, is cut into four on two threads and stays in three
// on three; either way within a level of one piece. A given --tile is taken as it is.
TEST_CASE("tiling cli: automatic tiles come in a multiple of the threads a strip") {
    TempFolder folder;
    const ddt::Image crop = ddt::test::photoCrop();
    ddt::Image wide = crop;  // the crop and its mirror side by side: 600 × 200
    wide.width = 2 * crop.width;
    wide.pixels.clear();
    const uint32_t c = crop.channels;
    for (uint32_t y = 0; y < crop.height; ++y) {
        const float* row = crop.pixels.data() + size_t(y) * crop.width * c;
        wide.pixels.insert(wide.pixels.end(), row, row + size_t(crop.width) * c);
        for (uint32_t x = crop.width; x-- > 0;) wide.pixels.insert(wide.pixels.end(), row + x * c, row + (x + 1) * c);
    }
    const std::string input = folder / "wide.png", whole = folder / "whole.png";
    ddt::writeImage(input, wide);
    REQUIRE(runDdtup({input, whole, "-s", "2", "-q", "--backend", "cpu", "--tile", "100000"}).exit_code == 0);
    for (const auto& [threads, tile, tiles] : {std::tuple{"2", "0", "4"}, {"3", "0", "3"}, {"2", "256", "3"}}) {
        CAPTURE(threads, tile);
        const std::string out = folder / "out.png";
        const Run run = runDdtup({input, out, "-s", "2", "--threads", threads, "--tile", tile, "--backend", "cpu",
                                  "--progress=json"});
        REQUIRE(run.exit_code == 0);
        std::set<std::string> seen;
        for (const auto& event : parseJsonLines(run.err)) {
            if (event.at("event") != "stage" || !event.count("tiles")) continue;
            CHECK(event.at("tiles") == tiles);  // one strip of 200 rows
            seen.insert(event.at("tile"));
        }
        CHECK(seen.size() == std::stoul(tiles));
        // Tiles against one piece: the project's bar for seams, within 1/255 on 99.9 % of the
        // samples (the flips near a crop's border may differ; on this photo they give the same bytes).
        CHECK(compareFiles(whole, out).within_one_level >= 0.999);
    }
}

// A JPEG or a PNG is decoded as the tiles reach its rows (core/image/row_decoder.h), while
// --mesh reads it whole: the image must be the same bytes either way. A file cut short after
// the rows of the first strips is still refused before the run (the reader reads it through
// first), with one line naming it once and nothing left behind.
TEST_CASE("tiling cli: an input decoded as the tiles reach its rows gives the image of one read whole") {
    TempFolder folder;
    const ddt::Image photo = ddt::test::photoCrop();
    for (const char* name : {"photo.jpg", "photo.png"}) {
        INFO(name);
        const std::string input = folder / name, rows = folder / "rows.png", whole = folder / "whole.png";
        ddt::writeImage(input, photo);
        REQUIRE(runDdtup({input, rows, "-s", "2", "--tile", "64", "-q", "--backend", "cpu"}).exit_code == 0);
        REQUIRE(runDdtup({input, whole, "-s", "2", "--tile", "64", "-q", "--backend", "cpu", "--mesh", folder / "mesh.ply"})
                    .exit_code == 0);
        CHECK(readFile(rows) == readFile(whole));
    }
    // Three quarters of the file: the first strips' rows are there, a later strip's are not.
    // (No note of the backend either: it is chosen only once an image is read.)
    const std::string cut = folder / "cut.jpg";
    ddt::writeImage(cut, photo);
    fs::resize_file(cut, fs::file_size(cut) * 3 / 4);
    const auto before = folder.names();
    const Run run = runDdtup({cut, folder / "out.png", "-s", "2", "--tile", "64", "--backend", "cpu"});
    requireOneLineError(run, 1, "cut.jpg", ": truncated or corrupt image (");
    CHECK(run.err.find("cut.jpg") == run.err.rfind("cut.jpg"));
    CHECK(folder.names() == before);
}

TEST_CASE("tiling cli: a device out of memory leads to smaller tiles, never a partial image", "[vulkan]") {
    TempFolder folder;
    const std::string input = writePhotoCrop(folder);
    const std::string whole = folder / "whole.png", retried = folder / "retried.png";
    // Test hook: allocations over the limit fail as VK_ERROR_OUT_OF_DEVICE_MEMORY would. The
    // consistent surface's largest buffer (9 supersamples of 16 bytes per pixel) needs 4 MiB
    // for the 64-pixel tiles to fit; the plain one fits 1 MiB.
    for (const auto& [mode, limit] : {std::pair{"plain", "1048576"}, std::pair{"consistent", "4194304"}}) {
        INFO(mode);
        REQUIRE(runDdtup({input, whole, "-s", "2", "-q", "--reconstruct", mode, "--backend", "vulkan"}).exit_code == 0);
        const Run run = runDdtup({input, retried, "-s", "2", "-q", "--reconstruct", mode, "--backend", "vulkan"},
                                 {std::string("DDTUP_TEST_DEVICE_MEMORY=") + limit});
        INFO("stderr: " << run.err);
        REQUIRE(run.exit_code == 0);
        CHECK(compareFiles(whole, retried).within_one_level >= 0.999);  // the bar, as above
    }

    // With too little memory for even the smallest tile: one line, no file.
    const Run hopeless =
        runDdtup({input, folder / "none.png", "-s", "2", "-q", "--backend", "vulkan"}, {"DDTUP_TEST_DEVICE_MEMORY=1000"});
    requireOneLineError(hopeless, 1, input, "not enough device memory even for 64×64 tiles");
    CHECK(!fs::exists(folder / "none.png"));
}

TEST_CASE("tiling cli: --tile below 64 is a usage error") {
    requireOneLineError(runDdtup({"a.png", "b.png", "--tile", "16"}), 2, "--tile", "at least 64");
}
