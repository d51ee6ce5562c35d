// Tiling through the executable: --tile gives the untiled image (seams invisible), progress
// names the tiles, and a device that runs out of memory (injected: DDTUP_TEST_DEVICE_MEMORY,
// since a real out-of-memory cannot be provoked in CI) leads to smaller tiles, never to a
// black or partial image.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "flat_json.h"
#include "image.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;

// A 300×200 crop of a photo, so tiles of 64 meet in every direction.
std::string writePhotoCrop(const TempFolder& folder) {
    const ddt::Image photo = ddt::readImage(std::string(DDTUP_TEST_DATA) + "/../../bench/data/real/astronaut.png");
    ddt::Image crop = photo;
    crop.width = 300;
    crop.height = 200;
    crop.pixels.clear();
    for (uint32_t y = 0; y < crop.height; ++y)
        crop.pixels.insert(crop.pixels.end(), photo.row(y + 100), photo.row(y + 100) + crop.rowFloats());
    const std::string path = folder / "photo.png";
    ddt::writeImage(path, crop);
    return path;
}

// The share of samples that differ by more than 1/255, and the largest difference.
struct Agreement {
    double differing_share = 1.0;
    float max_difference = 1.0f;
};

Agreement compare(const ddt::Image& a, const ddt::Image& b) {
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    REQUIRE(a.pixels.size() == b.pixels.size());
    Agreement agreement{0.0, 0.0f};
    size_t differing = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        const float difference = std::fabs(a.pixels[i] - b.pixels[i]);
        agreement.max_difference = std::max(agreement.max_difference, difference);
        differing += difference > 1.0f / 255.0f + 1e-6f;
    }
    agreement.differing_share = double(differing) / double(a.pixels.size());
    return agreement;
}

}  // namespace

TEST_CASE("tiling cli: --tile 64 gives the untiled image, and progress names the tiles") {
    TempFolder folder;
    const std::string input = writePhotoCrop(folder);
    for (const char* backend : {"vulkan", "cpu"}) {
        INFO(backend);
        const std::string whole = folder / "whole.png", tiled = folder / "tiled.png";
        REQUIRE(runDdtup({input, whole, "-s", "2", "-q", "--backend", backend}).exit_code == 0);
        const Run run = runDdtup({input, tiled, "-s", "2", "--tile", "64", "--progress=json", "--backend", backend});
        REQUIRE(run.exit_code == 0);
        const Agreement agreement = compare(ddt::readImage(whole), ddt::readImage(tiled));
        // The bar: within 1/255 on at least 99.9 % of the samples (overlap 16: all).
        CHECK(agreement.differing_share <= 0.001);
        CHECK(agreement.max_difference <= 1.0f / 255.0f + 1e-6f);
        std::set<std::string> tiles_seen;
        for (const auto& event : parseJsonLines(run.err))
            if (event.at("event") == "stage" && event.count("tiles")) {
                CHECK(event.at("tiles") == "20");  // 5 × 4 tiles of 64 over 300 × 200
                tiles_seen.insert(event.at("tile"));
            }
        CHECK(tiles_seen.size() == 20);
    }
}

TEST_CASE("tiling cli: a device out of memory leads to smaller tiles, never a partial image") {
    TempFolder folder;
    const std::string input = writePhotoCrop(folder);
    const std::string whole = folder / "whole.png", retried = folder / "retried.png";
    REQUIRE(runDdtup({input, whole, "-s", "2", "-q"}).exit_code == 0);
    // Test hook: allocations over 1 MiB fail as VK_ERROR_OUT_OF_DEVICE_MEMORY would.
    const Run run = runDdtup({input, retried, "-s", "2", "-q"}, {"DDTUP_TEST_DEVICE_MEMORY=1048576"});
    INFO("stderr: " << run.err);
    REQUIRE(run.exit_code == 0);
    const Agreement agreement = compare(ddt::readImage(whole), ddt::readImage(retried));
    CHECK(agreement.differing_share <= 0.001);

    // With too little memory for even the smallest tile: one line, no file.
    const Run hopeless = runDdtup({input, folder / "none.png", "-s", "2", "-q"}, {"DDTUP_TEST_DEVICE_MEMORY=1000"});
    requireOneLineError(hopeless, 1, input, "not enough device memory even for 64×64 tiles");
    CHECK(!fs::exists(folder / "none.png"));
}

TEST_CASE("tiling cli: --tile below 64 is a usage error") {
    requireOneLineError(runDdtup({"a.png", "b.png", "--tile", "16"}), 2, "--tile", "at least 64");
}
