// Volumes through the real executable: NRRD and NIfTI in and out with their geometry, per-axis
// factors, --slices, --stats, and the options and inputs that are refused in one line.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <OpenImageIO/imageio.h>

#include "image_file.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "volume.h"
#include "volume_file.h"

namespace {

// Writes an NRRD by hand (not by ddtup's writer): float samples, x fastest, with `geometry`
// lines (space, directions, origin).
void writeFloatNrrd(const std::string& path, std::array<uint32_t, 3> size, const std::vector<float>& values,
                    const std::string& geometry) {
    std::ofstream out(path, std::ios::binary);
    out << "NRRD0004\ntype: float\ndimension: 3\nsizes: " << size[0] << " " << size[1] << " " << size[2]
        << "\nendian: little\nencoding: raw\n"
        << geometry << "\n";
    out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
}

const std::string kLpsGeometry =
    "space: left-posterior-superior\nspace directions: (0.5,0,0) (0,0.5,0) (0,0,2.5)\nspace origin: (10,20,30)\n";

// v = x + 2y + 3z on a 6 × 5 × 4 grid: any tetrahedralization reproduces it exactly.
std::vector<float> ramp(std::array<uint32_t, 3> size) {
    std::vector<float> values;
    for (uint32_t z = 0; z < size[2]; ++z)
        for (uint32_t y = 0; y < size[1]; ++y)
            for (uint32_t x = 0; x < size[0]; ++x) values.push_back(float(x + 2 * y + 3 * z));
    return values;
}

// A ball of value 100 in a volume of 0: something for the flips to do.
std::vector<float> ball(std::array<uint32_t, 3> size) {
    std::vector<float> values;
    for (uint32_t z = 0; z < size[2]; ++z)
        for (uint32_t y = 0; y < size[1]; ++y)
            for (uint32_t x = 0; x < size[0]; ++x) {
                const double dx = x - 4.3, dy = y - 3.6, dz = z - 4.1;
                values.push_back(dx * dx + dy * dy + dz * dz < 9.0 ? 100.0f : 0.0f);
            }
    return values;
}

// Where output voxel i lies in the input's index frame, clamped to the voxel centres' box.
double clampedInputIndex(uint32_t i, uint32_t n, uint32_t m) {
    return std::clamp((i + 0.5) * n / m - 0.5, 0.0, double(n - 1));
}

// The largest difference between `out`, magnified from ramp(size), and the ramp at each output
// voxel's input position.
double worstRampError(const ddt::Volume& out, std::array<uint32_t, 3> size) {
    double worst = 0.0;
    for (uint32_t z = 0; z < out.size[2]; ++z)
        for (uint32_t y = 0; y < out.size[1]; ++y)
            for (uint32_t x = 0; x < out.size[0]; ++x) {
                const double want = clampedInputIndex(x, size[0], out.size[0]) + 2 * clampedInputIndex(y, size[1], out.size[1]) +
                                    3 * clampedInputIndex(z, size[2], out.size[2]);
                worst = std::max(worst, std::abs(out.at(x, y, z) - want));
            }
    return worst;
}

}  // namespace

TEST_CASE("volume cli: an NRRD magnified x2 reproduces a linear field and moves its frame") {
    TempFolder work;
    const std::array<uint32_t, 3> size = {6, 5, 4};
    writeFloatNrrd(work / "ramp.nrrd", size, ramp(size), kLpsGeometry);
    const Run run = runDdtup({work / "ramp.nrrd", "-s", "2", work / "out.nrrd", "-q"});
    REQUIRE(run.exit_code == 0);
    CHECK(run.err.empty());
    const ddt::Volume out = ddt::readVolume(work / "out.nrrd");
    REQUIRE(out.size == std::array<uint32_t, 3>{12, 10, 8});
    CHECK(out.type == ddt::VoxelType::f32);
    // Spacing n·s/m = s/2; the origin moves by half a new voxel minus half an old one:
    // 10 + 0.5 · (0.25 − 0.5), 20 + 0.5 · (−0.25), 30 + 2.5 · (−0.25).
    const double expected[3][4] = {{0.25, 0, 0, 9.875}, {0, 0.25, 0, 19.875}, {0, 0, 1.25, 29.375}};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) CHECK(out.index_to_world.m[r][c] == Approx(expected[r][c]).margin(1e-12));
    // Float samples of values up to 21: the interpolation's rounding in float, a few ulps.
    CHECK(worstRampError(out, size) < 1e-4);
}

TEST_CASE("volume cli: per-axis factors, NIfTI output and --stats on a ball") {
    TempFolder work;
    const std::array<uint32_t, 3> size = {9, 8, 9};
    writeFloatNrrd(work / "ball.nrrd", size, ball(size), kLpsGeometry);
    const Run run = runDdtup({work / "ball.nrrd", "-s", "1,1.5,2.5", work / "ball.nii.gz", "--stats", "-q"});
    REQUIRE(run.exit_code == 0);
    CHECK(run.err.empty());
    CHECK_THAT(run.out, Catch::Contains("volume         9 x 8 x 9 -> 9 x 12 x 23"));
    // The ball's surface leaves flips to do (their count is the optimizer's business: tested
    // in test_tet_lawson.cpp); --stats reports them, and the cost falls.
    CHECK_THAT(run.out, Catch::Contains("flips"));
    const size_t init = run.out.find("cost-init"), final = run.out.find("cost-final");
    REQUIRE((init != std::string::npos && final != std::string::npos));
    CHECK(std::stod(run.out.substr(final + 10)) < std::stod(run.out.substr(init + 9)));
    const ddt::Volume out = ddt::readVolume(work / "ball.nii.gz");
    CHECK(out.size == std::array<uint32_t, 3>{9, 12, 23});
    // Interpolated values stay within the input's range.
    for (float v : out.values) REQUIRE((v >= 0.0f && v <= 100.0f));
}

TEST_CASE("volume cli: --slices writes the output's three middle planes") {
    TempFolder work;
    const std::array<uint32_t, 3> size = {6, 5, 4};
    writeFloatNrrd(work / "ramp.nrrd", size, ramp(size), kLpsGeometry);
    const Run run = runDdtup({work / "ramp.nrrd", "-s", "2", work / "out.nii", "--slices", work / "views", "-q"});
    REQUIRE(run.exit_code == 0);
    const ddt::Image axial = ddt::readImage(work / "views/out-axial.png");
    CHECK((axial.width == 12 && axial.height == 10));
    const ddt::Image coronal = ddt::readImage(work / "views/out-coronal.png");
    CHECK((coronal.width == 12 && coronal.height == 8));
    const ddt::Image sagittal = ddt::readImage(work / "views/out-sagittal.png");
    CHECK((sagittal.width == 10 && sagittal.height == 8));
}

TEST_CASE("volume cli: options that mean nothing for volumes are refused in one line") {
    TempFolder work;
    const std::array<uint32_t, 3> size = {6, 5, 4};
    const std::string in = work / "ramp.nrrd";
    writeFloatNrrd(in, size, ramp(size), kLpsGeometry);
    for (const std::vector<std::string>& extra : std::vector<std::vector<std::string>>{
             {"--mesh", work / "m.ply"}, {"--quality", "80"}, {"--simplify", "0.5"}, {"--width", "20"},
             {"--reconstruct", "plain"}, {"--depth", "half"}}) {
        INFO(extra[0]);
        std::vector<std::string> args = {in, work / "out.nrrd"};
        args.insert(args.end(), extra.begin(), extra.end());
        requireOneLineError(runDdtup(args), 2, in, "does not apply to volumes");
    }
    requireOneLineError(runDdtup({in, "-s", "2,2", work / "out.nrrd"}), 2, "--scale", "three");
    requireOneLineError(runDdtup({in, "-s", "2,0.5,2", work / "out.nrrd"}), 2, "--scale", ">= 1");
    requireOneLineError(runDdtup({in, work / "out.png"}), 2, "out.png", "volume file");
    requireOneLineError(runDdtup({in, work / "out.nrrd", "--cost", "sederberg"}), 2, "--cost sederberg", "variance or face-scf");
    requireOneLineError(runDdtup({in, work / "out.nrrd", "--cost", "area"}), 2, "--cost area", "sederberg, variance or face-scf");
    REQUIRE(runDdtup({in, "-s", "1", work / "copy.nrrd", "-q"}).exit_code == 0);
    CHECK(work.names() == std::set<std::string>{"copy.nrrd", "ramp.nrrd"});
}

TEST_CASE("volume cli: per-axis factors and --slices are refused for images") {
    TempFolder work;
    const std::string image = std::string(DDTUP_TEST_DATA) + "/crop32_astronaut.png";
    requireOneLineError(runDdtup({image, "-s", "1,1,2", work / "out.png"}), 2, "--scale", "volumes");
    requireOneLineError(runDdtup({image, work / "out.png", "--slices", work / "v"}), 2, "--slices", "volumes");
    requireOneLineError(runDdtup({image, work / "out.nii"}), 2, "out.nii", "image file");
    CHECK(work.names().empty());
}

TEST_CASE("volume cli: a batch goes past a bad volume and writes nothing for it") {
    TempFolder work;
    const std::array<uint32_t, 3> size = {6, 5, 4};
    writeFloatNrrd(work / "good.nrrd", size, ramp(size), kLpsGeometry);
    // The header promises 6 × 5 × 4 floats; the data stops after 10.
    std::vector<float> short_data = ramp(size);
    short_data.resize(10);
    writeFloatNrrd(work / "short.nrrd", size, short_data, kLpsGeometry);
    const Run run = runDdtup({work / "short.nrrd", work / "good.nrrd", "-o", work / "out", "-q"});
    CHECK(run.exit_code == 1);
    // The error, then the batch's summary (printed even with -q).
    CHECK_THAT(run.err, Catch::StartsWith("ddtup: " + (work / "short.nrrd") + ": truncated"));
    CHECK_THAT(run.err, Catch::Contains("1 done, 0 skipped, 1 failed"));
    CHECK(ddt::readVolume(work / "out/good.nrrd").size == std::array<uint32_t, 3>{12, 10, 8});
    std::set<std::string> written;
    for (const auto& entry : std::filesystem::directory_iterator(work / "out")) written.insert(entry.path().filename().string());
    CHECK(written == std::set<std::string>{"good.nrrd"});
}

TEST_CASE("volume cli: --tile cuts a volume into bricks, seamlessly for a linear field") {
    TempFolder work;
    const std::array<uint32_t, 3> size = {70, 4, 3};
    writeFloatNrrd(work / "long.nrrd", size, ramp(size), kLpsGeometry);
    const Run run = runDdtup({work / "long.nrrd", "-s", "2", work / "out.nrrd", "--tile", "64", "--stats", "-q"});
    REQUIRE(run.exit_code == 0);
    CHECK_THAT(run.out, Catch::Contains("bricks         2"));
    const ddt::Volume out = ddt::readVolume(work / "out.nrrd");
    REQUIRE(out.size == std::array<uint32_t, 3>{140, 8, 6});
    // Values up to 81 stored as float: a few ulps (2^-17 at 64–128).
    CHECK(worstRampError(out, size) < 1e-4);
}

namespace {

// A grey image whose pixel (x, y) holds level (x + width·y + offset) / scale.
ddt::Image greyImage(uint32_t width, uint32_t height, uint32_t channels, int offset, ddt::SampleType type) {
    ddt::Image image;
    image.width = width;
    image.height = height;
    image.channels = channels;
    image.sample_type = type;
    const float scale = type == ddt::SampleType::UInt8 ? 255.0f : 65535.0f;
    for (uint32_t i = 0; i < width * height * channels; ++i) image.pixels.push_back(float(i / channels + offset) / scale);
    return image;
}

}  // namespace

TEST_CASE("volume cli: --stack reads a folder of slices and a multi-page TIFF") {
    TempFolder work;
    std::filesystem::create_directory(work / "slices");
    for (int k = 0; k < 3; ++k)
        ddt::writeImage(work / ("slices/s" + std::to_string(k) + ".png"), greyImage(4, 3, 1, 20 * k, ddt::SampleType::UInt8));
    Run run = runDdtup({"--stack", work / "slices", "-s", "1", work / "v.nrrd", "-q"});
    REQUIRE(run.exit_code == 0);
    ddt::Volume volume = ddt::readVolume(work / "v.nrrd");
    REQUIRE(volume.size == std::array<uint32_t, 3>{4, 3, 3});
    CHECK(volume.type == ddt::VoxelType::u8);
    // x1 gives the input back: slice k's voxel (x, y) is level x + 4y + 20k.
    for (uint32_t z = 0; z < 3; ++z)
        for (uint32_t y = 0; y < 3; ++y)
            for (uint32_t x = 0; x < 4; ++x) REQUIRE(volume.at(x, y, z) == float(x + 4 * y + 20 * z));

    // Two 16-bit pages in one TIFF, written by OpenImageIO.
    {
        auto out = OIIO::ImageOutput::create(work / "pages.tif");
        REQUIRE(out);
        OIIO::ImageSpec specs[2] = {OIIO::ImageSpec(5, 2, 1, OIIO::TypeDesc::UINT16), OIIO::ImageSpec(5, 2, 1, OIIO::TypeDesc::UINT16)};
        REQUIRE(out->open(work / "pages.tif", 2, specs));
        for (int page = 0; page < 2; ++page) {
            if (page) REQUIRE(out->open(work / "pages.tif", specs[page], OIIO::ImageOutput::AppendSubimage));
            std::vector<uint16_t> levels;
            for (int i = 0; i < 10; ++i) levels.push_back(uint16_t(1000 * page + 7 * i));
            REQUIRE(out->write_image(OIIO::TypeDesc::UINT16, levels.data()));
        }
        REQUIRE(out->close());
    }
    run = runDdtup({"--stack", work / "pages.tif", "-s", "1", work / "p.nii", "-q"});
    REQUIRE(run.exit_code == 0);
    volume = ddt::readVolume(work / "p.nii");
    REQUIRE(volume.size == std::array<uint32_t, 3>{5, 2, 2});
    CHECK(volume.type == ddt::VoxelType::u16);
    CHECK(volume.at(3, 1, 1) == float(1000 + 7 * 8));
}

TEST_CASE("volume cli: --stack refuses what is not a stack of grey slices") {
    TempFolder work;
    std::filesystem::create_directory(work / "colour");
    ddt::writeImage(work / "colour/a.png", greyImage(4, 3, 1, 0, ddt::SampleType::UInt8));
    ddt::writeImage(work / "colour/b.png", greyImage(4, 3, 3, 0, ddt::SampleType::UInt8));
    requireOneLineError(runDdtup({"--stack", work / "colour", work / "v.nrrd", "-q"}), 1, "b.png", "must be grey");
    std::filesystem::create_directory(work / "sizes");
    ddt::writeImage(work / "sizes/a.png", greyImage(4, 3, 1, 0, ddt::SampleType::UInt8));
    ddt::writeImage(work / "sizes/b.png", greyImage(3, 4, 1, 0, ddt::SampleType::UInt8));
    requireOneLineError(runDdtup({"--stack", work / "sizes", work / "v.nrrd", "-q"}), 1, "b.png", "the first slice 4×3");
    std::filesystem::create_directory(work / "one");
    ddt::writeImage(work / "one/a.png", greyImage(4, 3, 1, 0, ddt::SampleType::UInt8));
    requireOneLineError(runDdtup({"--stack", work / "one", work / "v.nrrd", "-q"}), 1, "one", "at least 2");
    requireOneLineError(runDdtup({"--stack", work / "one", work / "v.png"}), 2, "v.png", "volume file");
    requireOneLineError(runDdtup({"--stack", work / "one", work / "sizes", "-o", work / "out"}), 2, "--stack", "one folder");
    CHECK(!std::filesystem::exists(work / "v.nrrd"));
}

TEST_CASE("volume cli: --backend vulkan flips on the device by the parallel rule", "[heavy][vulkan]") {
    TempFolder work;
    const std::array<uint32_t, 3> size = {9, 8, 9};
    writeFloatNrrd(work / "ball.nrrd", size, ball(size), kLpsGeometry);
    writeFloatNrrd(work / "ramp.nrrd", size, ramp(size), kLpsGeometry);
    for (const std::string cost : {"variance", "face-scf"}) {
        INFO(cost);
        // The rule's meshes equal its CPU version's (test_tet_vulkan.cpp); here: it runs through
        // the executable, says so, lowers the cost and leaves a linear field linear.
        Run run = runDdtup({work / "ball.nrrd", work / "out.nrrd", "--backend", "vulkan", "--cost", cost, "--stats", "-q"});
        REQUIRE(run.exit_code == 0);
        CHECK(run.err.empty());  // validation (scripts/test turns it on) says nothing
        CHECK_THAT(run.out, Catch::Contains("the parallel rule on the Vulkan device"));
        CHECK_THAT(run.out, Catch::Contains("rounds"));
        const size_t init = run.out.find("cost-init"), final = run.out.find("cost-final");
        REQUIRE((init != std::string::npos && final != std::string::npos));
        CHECK(std::stod(run.out.substr(final + 10)) < std::stod(run.out.substr(init + 9)));
        run = runDdtup({work / "ramp.nrrd", work / "ramp2.nrrd", "--backend", "vulkan", "--cost", cost, "-q"});
        REQUIRE(run.exit_code == 0);
        // Float samples of values up to 45: a few of float's ulps.
        CHECK(worstRampError(ddt::readVolume(work / "ramp2.nrrd"), size) < 1e-4);
    }
}

TEST_CASE("volume cli: --backend vulkan resamples on the device, the CPU's bytes where both flip alike", "[vulkan]") {
    TempFolder work;
    // Steps along x and z: both optimizers make the same few flips (a precondition, checked by
    // --stats; the meshes' equality is test_tet_vulkan.cpp's), and the resampling interpolates
    // across both steps, so the outputs agree byte for byte only if the device's resampling is
    // the CPU's.
    const std::array<uint32_t, 3> size = {9, 8, 9};
    std::vector<float> steps;
    for (uint32_t z = 0; z < size[2]; ++z)
        for (uint32_t y = 0; y < size[1]; ++y)
            for (uint32_t x = 0; x < size[0]; ++x) steps.push_back((x >= 4 ? 100.0f : 0.0f) + (z >= 5 ? 7.0f : 0.0f));
    writeFloatNrrd(work / "steps.nrrd", size, steps, kLpsGeometry);
    auto bytesOf = [](const std::string& path) {
        std::ifstream file(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(file), {});
    };
    auto flipsLine = [](const std::string& out) {
        const size_t at = out.find("flips");
        return at == std::string::npos ? std::string() : out.substr(at, out.find('\n', at) - at);
    };
    for (const std::string factors : {"2", "3,2,1.5"}) {
        INFO("-s " << factors);
        const Run cpu = runDdtup({work / "steps.nrrd", "-s", factors, work / "cpu.nrrd", "--backend", "cpu", "--stats", "-q"});
        const Run vulkan =
            runDdtup({work / "steps.nrrd", "-s", factors, work / "vulkan.nrrd", "--backend", "vulkan", "--stats", "-q"});
        REQUIRE(cpu.exit_code == 0);
        REQUIRE(vulkan.exit_code == 0);
        CHECK(vulkan.err.empty());  // validation (scripts/test turns it on) says nothing
        CHECK_THAT(vulkan.out, Catch::Contains("in its tetrahedron, on the Vulkan device"));
        REQUIRE(flipsLine(cpu.out) != "");
        REQUIRE(flipsLine(vulkan.out) == flipsLine(cpu.out));
        const std::string cpu_bytes = bytesOf(work / "cpu.nrrd");
        CHECK(cpu_bytes.size() > 9 * 8 * 9 * 4);
        CHECK(bytesOf(work / "vulkan.nrrd") == cpu_bytes);
    }
}
