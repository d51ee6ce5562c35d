// Every input kind (an image, an image with a mask, a point file, a volume) with every option
// that shapes a run (tiles, a mesh file, simplification, the cost, the surface, the fallback,
// the backend):
// each cell either works — exit 0 and an output of the magnified size — or is refused — one
// line naming the option, exit 2 and no output. docs/USAGE.md's "Combinations" lists the
// same cells: a cell that changes changes both.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "image_file.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"
#include "volume.h"
#include "volume_file.h"

namespace {

using namespace ddt;

// 96 × 80: tiles of 64 (the smallest --tile) cut it into several.
constexpr uint32_t kWidth = 96, kHeight = 80;
constexpr uint32_t kVolumeSide = 8;

enum class Kind { image, mask, points, volume };

const char* kindName(Kind kind) {
    switch (kind) {
        case Kind::image: return "image";
        case Kind::mask: return "image with --mask";
        case Kind::points: return "point file";
        case Kind::volume: return "volume";
    }
    return "";
}

struct Option {
    std::vector<std::string> args;
    // Per kind (image, mask, points, volume): "" where the option works, else what the one
    // line of its refusal says.
    std::string refusal[4];
};

// The inputs of each kind, written once per test run into `folder`.
struct Inputs {
    explicit Inputs(const TempFolder& folder) : dir(folder.path()) {
        std::mt19937 rng(21);
        Image image = test::randomImage(rng, kWidth, kHeight, 3, 256);
        writeImage(dir / "in.png", image);
        std::vector<float> mask(size_t(kWidth) * kHeight * 3, 1.0f);
        for (uint32_t y = 30; y < 50; ++y)
            for (uint32_t x = 40; x < 70; ++x)
                for (uint32_t k = 0; k < 3; ++k) mask[(size_t(y) * kWidth + x) * 3 + k] = 0.0f;
        writeImage(dir / "mask.png", test::makeImage(kWidth, kHeight, 3, mask));
        std::ofstream points(dir / "points.csv");
        std::uniform_real_distribution<double> x(0.0, kWidth - 1.0), y(0.0, kHeight - 1.0);
        std::uniform_int_distribution<int> level(0, 255);
        for (int i = 0; i < 200; ++i)
            points << x(rng) << "," << y(rng) << "," << level(rng) << "," << level(rng) << "," << level(rng) << "\n";
        std::ofstream volume(dir / "in.nrrd", std::ios::binary);
        volume << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: " << kVolumeSide << " " << kVolumeSide << " "
               << kVolumeSide << "\nencoding: raw\n\n";
        for (uint32_t i = 0; i < kVolumeSide * kVolumeSide * kVolumeSide; ++i) volume.put(char(level(rng)));
    }

    // The command line of `kind` magnified ×2 into `out`.
    std::vector<std::string> command(Kind kind, const std::string& out) const {
        switch (kind) {
            case Kind::image: return {dir / "in.png", "-s", "2", out};
            case Kind::mask: return {dir / "in.png", "--mask", dir / "mask.png", "-s", "2", out};
            case Kind::points:
                return {dir / "points.csv", "--frame", std::to_string(kWidth) + "x" + std::to_string(kHeight), "-s",
                        "2", out};
            case Kind::volume: return {dir / "in.nrrd", "-s", "2", out};
        }
        return {};
    }

    std::filesystem::path dir;
};

void checkCell(const Inputs& inputs, Kind kind, const Option& option, const std::string& mesh_file) {
    const std::string out = inputs.dir / (kind == Kind::volume ? "out.nrrd" : "out.png");
    std::filesystem::remove(out);
    std::filesystem::remove(mesh_file);
    std::vector<std::string> args = inputs.command(kind, out);
    args.insert(args.end(), option.args.begin(), option.args.end());
    args.push_back("-q");
    std::string line;
    for (const std::string& arg : args) line += " " + arg;
    INFO(kindName(kind) << ":" << line);
    const Run run = runDdtup(args);
    const std::string& refusal = option.refusal[int(kind)];
    if (!refusal.empty()) {
        requireOneLineError(run, 2, option.args.front(), refusal);
        CHECK_FALSE(std::filesystem::exists(out));
        CHECK_FALSE(std::filesystem::exists(mesh_file));
        return;
    }
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    if (kind == Kind::volume) {
        const Volume volume = readVolume(out);
        CHECK(volume.size == std::array<uint32_t, 3>{2 * kVolumeSide, 2 * kVolumeSide, 2 * kVolumeSide});
    } else {
        const Image image = readImage(out);
        CHECK(image.width == 2 * kWidth);
        CHECK(image.height == 2 * kHeight);
    }
    if (option.args.front() == "--mesh") CHECK(std::filesystem::file_size(mesh_file) > 0);
}

}  // namespace

TEST_CASE("cli: every input kind with every option either works or is refused with one line", "[vulkan]") {
    TempFolder folder;
    const Inputs inputs(folder);
    const std::string mesh_file = folder / "mesh.ply";
    const std::string whole = "one piece; --tile does not apply";
    const std::vector<Option> options = {
        {{"--tile", "64"}, {"", whole, whole, ""}},
        {{"--mesh", mesh_file},
         {"", "do not combine yet", "do not combine yet", "does not apply to volumes"}},
        {{"--simplify", "0.5"}, {"", "do not combine yet", "do not combine yet", "does not apply to volumes"}},
        {{"--cost", "variance"}, {"", "", "", ""}},
        {{"--reconstruct", "plain"}, {"", "", "", "does not apply to volumes"}},
        {{"--reconstruct", "consistent"},
         {"", "needs every pixel's value", "needs a full image", "does not apply to volumes"}},
        {{"--fallback", "lanczos3"},
         {"", "have no input to convolve", "no pixel grid to convolve", "does not apply to volumes"}},
        {{"--backend", "cpu"}, {"", "", "", ""}},
        {{"--backend", "vulkan"}, {"", "", "", ""}},
    };
    for (Kind kind : {Kind::image, Kind::mask, Kind::points, Kind::volume})
        for (const Option& option : options) checkCell(inputs, kind, option, mesh_file);
}
