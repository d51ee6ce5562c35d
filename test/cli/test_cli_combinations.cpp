// Every input kind (an image, an image with a mask, a point file, a volume) with every option
// that shapes a run (tiles, a mesh file, simplification, the cost, the surface, the fallback,
// the backend):
// each cell either works — exit 0 and an output of the magnified size — or is refused — one
// line naming the option, exit 2 and no output. The README's "What combines" table marks the
// same cells (checked below) and docs/USAGE.md's "Combinations" gives the reasons: a cell that
// changes changes all three.
#include <catch2/catch.hpp>

#include <algorithm>
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
    std::string readme_row;  // the first cell of the README's row for it
};

// The options of the matrix; a mesh file is written to `mesh_file`.
std::vector<Option> matrixOptions(const std::string& mesh_file) {
    const std::string volumes = "does not apply to volumes";
    const std::string cost_and_backend = "`--cost W`, `--backend cpu`/`vulkan`";
    return {
        {{"--tile", "64"}, {"", "", "", ""}, "`--tile N`"},
        {{"--mesh", mesh_file}, {"", "", "", volumes}, "`--mesh F`"},
        {{"--simplify", "0.5"}, {"", "", "", volumes}, "`--simplify R`, `--max-error E`"},
        {{"--cost", "variance"}, {"", "", "", ""}, cost_and_backend},
        {{"--reconstruct", "plain"}, {"", "", "", volumes}, "`--reconstruct plain`"},
        {{"--reconstruct", "consistent"}, {"", "needs every pixel's value", "needs a full image", volumes},
         "`--reconstruct consistent`"},
        {{"--fallback", "lanczos3"}, {"", "have no input to convolve", "no pixel grid to convolve", volumes},
         "`--fallback lanczos3`"},
        {{"--delaunay", "device"}, {"applies to masks and point files", "", "", volumes}, "`--delaunay device`"},
        {{"--backend", "cpu"}, {"", "", "", ""}, cost_and_backend},
        {{"--backend", "vulkan"}, {"", "", "", ""}, cost_and_backend},
    };
}

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
    const std::vector<Option> options = matrixOptions(mesh_file);
    for (Kind kind : {Kind::image, Kind::mask, Kind::points, Kind::volume})
        for (const Option& option : options) checkCell(inputs, kind, option, mesh_file);
}

// The README's table is what users read: each of its cells must say ✓ exactly where the
// matrix above runs the option, ✗ where it is refused.
TEST_CASE("cli: the README's table of combinations marks the cells the matrix tests") {
    std::ifstream readme(std::string(DDTUP_TEST_DATA) + "/../../README.md");
    REQUIRE(readme);
    std::vector<std::string> rows;  // the table's, under the heading "What combines"
    bool in_section = false;
    for (std::string line; std::getline(readme, line);) {
        if (line.rfind("#", 0) == 0) in_section = line == "### What combines";
        if (in_section && line.rfind("| `", 0) == 0) rows.push_back(line);
    }
    for (const Option& option : matrixOptions("mesh.ply")) {
        INFO(option.readme_row);
        const std::string start = "| " + option.readme_row + " |";
        const auto row = std::find_if(rows.begin(), rows.end(), [&](const std::string& r) { return r.rfind(start, 0) == 0; });
        REQUIRE(row != rows.end());
        std::vector<std::string> cells;
        for (size_t at = start.size(); at < row->size();) {
            const size_t end = row->find('|', at);
            if (end == std::string::npos) break;
            std::string cell = row->substr(at, end - at);
            cell.erase(0, cell.find_first_not_of(' '));
            cells.push_back(cell);
            at = end + 1;
        }
        REQUIRE(cells.size() == 4);
        for (Kind kind : {Kind::image, Kind::mask, Kind::points, Kind::volume}) {
            INFO(kindName(kind));
            const bool works = option.refusal[int(kind)].empty();
            CHECK(cells[size_t(kind)].rfind(works ? "✓" : "✗", 0) == 0);
        }
    }
}
