// A point file in tiles through the real executable (app/delaunay/sampled_tile.h): --tile and
// automatic tiles (the one-piece mesh and output beyond --memory) give the one-piece output's
// bytes, on both backends, for points anywhere and for points on pixel centres (which tile as
// a mask's known pixels).
#include <catch2/catch.hpp>

#include <array>
#include <random>
#include <sstream>

#include "image_file.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

using namespace ddt;

// Every pixel of the two files, compared as decoded (the PNG encoder's bytes are its own).
size_t differingSamples(const std::string& a, const std::string& b) {
    const Image x = readImage(a), y = readImage(b);
    REQUIRE(x.width == y.width);
    REQUIRE(x.height == y.height);
    REQUIRE(x.pixels.size() == y.pixels.size());
    size_t differing = 0;
    for (size_t i = 0; i < x.pixels.size(); ++i) differing += x.pixels[i] != y.pixels[i];
    return differing;
}

// 8-bit RGB points of a w × h frame, none inside the discs (x, y, radius): `count` at random
// places, or with `centres` each pixel centre with a chance of 1/2.
std::string pointsCsv(uint32_t w, uint32_t h, int count, bool centres, const std::vector<std::array<double, 3>>& gaps) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> x(0.0, w - 1.0), y(0.0, h - 1.0);
    std::uniform_int_distribution<int> level(0, 255);
    std::ostringstream csv;
    csv << "x,y,r,g,b\n";
    const int candidates = centres ? int(w * h) : count;
    for (int i = 0; i < candidates; ++i) {
        double px = x(rng), py = y(rng);
        if (centres) {
            px = i % w, py = i / w;
            if (level(rng) < 128) continue;
        }
        bool in_gap = false;
        for (const auto& [cx, cy, r] : gaps) in_gap = in_gap || (px - cx) * (px - cx) + (py - cy) * (py - cy) < r * r;
        if (in_gap) continue;
        // Bands of colour with a step every 24 pixels: edges for the flips to follow.
        const int band = (int(px + py) / 24) % 2 ? 220 : 30;
        csv << px << ',' << py << ',' << band << ',' << level(rng) << ',' << int(px) % 256 << '\n';
    }
    return csv.str();
}

}  // namespace

TEST_CASE("cli point tiles: tiled outputs are the one-piece output's pixels", "[delaunay][vulkan]") {
    TempFolder work;
    const uint32_t w = 300, h = 200;
    // Gaps across the 64- and 128-pixel tiles' borders, one wider than the overlap, and on the
    // frame's corners and edges.
    const std::vector<std::array<double, 3>> gaps = {{64, 64, 14}, {128, 100, 36}, {0, 0, 12},
                                                     {299, 199, 9}, {0, 150, 8}, {200, 0, 10}};
    const std::string anywhere = work / "anywhere.csv", centres = work / "centres.csv";
    writeText(anywhere, pointsCsv(w, h, int(w * h / 10), false, gaps));
    writeText(centres, pointsCsv(w, h, 0, true, gaps));  // dense: the pixel form
    const std::string frame = std::to_string(w) + "x" + std::to_string(h);
    for (const std::string& points : {anywhere, centres})
        for (const std::string backend : {"cpu", "vulkan"}) {
            INFO(points << ", " << backend);
            const std::string whole = work / "whole.png";
            auto run = [&](const std::string& out, const std::string& scale, std::vector<std::string> more) {
                std::vector<std::string> args = {points, "--frame", frame, "-s", scale, out, "--backend", backend, "-q"};
                args.insert(args.end(), more.begin(), more.end());
                const Run result = runDdtup(args);
                INFO(result.err);
                REQUIRE(result.exit_code == 0);
            };
            for (const std::string scale : {"1", "2"}) {
                INFO("-s " << scale);
                run(whole, scale, {});
                for (const std::string side : {"64", "128"}) {
                    INFO("--tile " << side);
                    run(work / "tiled.png", scale, {"--tile", side});
                    CHECK(differingSamples(whole, work / "tiled.png") == 0);
                }
            }
            // ×5 in one piece needs about 18 MB for its output alone, beyond what --memory 16M
            // leaves (14 MB): tiles, where before the job was refused.
            run(whole, "5", {});
            run(work / "automatic.png", "5", {"--memory", "16M"});
            CHECK(differingSamples(whole, work / "automatic.png") == 0);
        }
}
