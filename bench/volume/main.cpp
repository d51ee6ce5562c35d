// ddtup-bench-volume: the volume bench of bench/README.md. Each synthetic volume is shrunk by
// area averaging (by 2, and by 4 from 64³ up) and magnified back by trilinear and tricubic
// (Catmull–Rom) interpolation, by the linear interpolation on the initial Kuhn mesh, and by the
// DDT of Tóth et al. with each weight (serial generalized Lawson); each result is scored against
// the noise-free original: PSNR over the original's data range, and the mean distance between
// the isosurfaces of original and result. Writes a Markdown table, a CSV and slice crops.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "grid_filters.h"
#include "image.h"
#include "image_file.h"
#include "context.h"
#include "tet_mesh.h"
#include "volume/tet_device.h"
#include "tet_resample.h"
#include "test_volumes.h"
#include "volume_magnify.h"
#include "volume_metrics.h"

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

struct Method {
    std::string name;
    double optimize_s = 0.0;  // build the mesh and flip (DDT only)
    double resample_s = 0.0;
    uint64_t flips = 0;
    ddt::Volume result;
};

// The isosurface level: the middle of the range, except for Shepp–Logan, whose only surface at
// 0.5 is the skull, thinner than a voxel at these sizes; at 0.1 it is the brain's boundary
// against the ventricles and the space inside the skull (the brain is 0.2, those 0).
double surfaceLevel(bench::TestVolumeKind kind) { return kind == bench::TestVolumeKind::shepp_logan ? 0.1 : 0.5; }

Method magnifyByGrid(const std::string& name, const ddt::Volume& small, const std::array<uint32_t, 3>& size,
                     bench::GridFilter filter) {
    Method method;
    method.name = name;
    const auto start = Clock::now();
    method.result = bench::resampleGrid(small, size, filter);
    method.resample_s = secondsSince(start);
    return method;
}

// The linear interpolation on the initial Kuhn mesh: what the flips start from.
Method magnifyByKuhnMesh(const ddt::Volume& small, const std::array<uint32_t, 3>& size) {
    Method method;
    method.name = "Kuhn mesh, no flips";
    auto start = Clock::now();
    const ddt::TetMesh mesh = ddt::kuhnTetMesh(small.size);
    method.optimize_s = secondsSince(start);
    start = Clock::now();
    method.result.size = size;
    method.result.values = ddt::resampleTets(mesh, small.values, size);
    method.resample_s = secondsSince(start);
    return method;
}

// ddtup's way (core/volume/volume_magnify.h): serial flips, or with `context` the parallel
// rule on that Vulkan device (compute/volume/tet_device.h), whose memory inventory it prints:
// the device arrays' bytes and the bytes zeroed (on lavapipe, where device memory is host
// memory, only written pages become resident: the zeroed arrays and the slots in use).
Method magnifyByDdt(const std::string& name, const ddt::Volume& small, const std::array<uint32_t, 3>& size,
                    ddt::TetWeight weight, ddt::VulkanContext* context = nullptr) {
    Method method;
    method.name = name;
    ddt::VolumeMagnifyOptions options;
    options.weight = weight;
    if (context)
        options.optimize = [context, &name, &small](ddt::TetMesh& mesh, ddt::TetCostField&& field, ddt::TetWeight w) {
            ddt::TetParallelOptions parallel;
            parallel.weight = w;
            const uint32_t slots = mesh.slotCount();
            ddt::TetDeviceReport report;
            const ddt::TetParallelStats rule = ddt::optimizeTetMeshVulkan(*context, mesh, field, parallel, {}, &report);
            constexpr double kMiB = 1024.0 * 1024.0;
            std::printf("%s, %u³ input: %u slots, device arrays %.1f MiB (%.1f bytes a slot), zeroed %.1f MiB "
                        "(%.1f bytes a slot)\n",
                        name.c_str(), small.size[0], slots, double(report.device_bytes) / kMiB,
                        double(report.device_bytes) / slots, double(report.zeroed_bytes) / kMiB,
                        double(report.zeroed_bytes) / slots);
            ddt::TetLawsonStats stats;
            stats.flips = rule.flips;
            return stats;
        };
    ddt::VolumeMagnifyStats stats;
    method.result.size = size;
    method.result.values = ddt::magnifyVolumeValues(small, size, options, stats);
    method.flips = stats.lawson.flipCount();
    method.optimize_s = stats.optimize_s;
    method.resample_s = stats.resample_s;
    return method;
}

// The middle axial slice of each volume side by side, grey over [0, 1] (every test volume's
// nominal range), each voxel a block of `zoom` pixels so that a staircase is visible.
void writeCrops(const std::string& path, const std::vector<const ddt::Volume*>& volumes, uint32_t zoom) {
    const uint32_t n = volumes.front()->size[0], gap = 4;
    ddt::Image image;
    image.width = uint32_t(volumes.size()) * (n * zoom + gap) - gap;
    image.height = volumes.front()->size[1] * zoom;
    image.channels = 1;
    image.pixels.assign(size_t(image.width) * image.height, 1.0f);
    const uint32_t z = volumes.front()->size[2] / 2;
    for (size_t k = 0; k < volumes.size(); ++k)
        for (uint32_t y = 0; y < image.height; ++y)
            for (uint32_t x = 0; x < n * zoom; ++x)
                image.pixels[size_t(y) * image.width + k * (n * zoom + gap) + x] =
                    std::clamp(volumes[k]->at(x / zoom, y / zoom, z), 0.0f, 1.0f);
    ddt::writeImage(path, image);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"ddtup-bench-volume: DDT on volumes against trilinear and tricubic interpolation"};
    std::vector<uint32_t> sizes = {32, 64, 128};
    std::vector<std::string> volume_names = {"sphere", "shepp-logan", "slanted-interface"};
    std::vector<double> noises = {0.0, 0.05};
    std::string out = "volume-bench";
    bool quick = false;
    app.add_option("--sizes", sizes, "Sides of the original cubes")->delimiter(',')->capture_default_str();
    app.add_option("--volumes", volume_names, "sphere, shepp-logan, slanted-interface")->delimiter(',')->capture_default_str();
    app.add_option("--noise", noises, "Gaussian noise sigmas added to the originals (0: none)")->delimiter(',')->capture_default_str();
    app.add_option("--out", out, "Folder for the table, the CSV and the crops")->capture_default_str();
    app.add_flag("--quick", quick, "One 16³ sphere, no noise: CI's check that the bench runs");
    bool vulkan = false;
    app.add_flag("--vulkan", vulkan, "Also DDT by the parallel rule on the first Vulkan device (rows \"…, Vulkan\")");
    CLI11_PARSE(app, argc, argv);
    if (quick) {
        sizes = {16};
        volume_names = {"sphere"};
        noises = {0.0};
    }
    std::vector<bench::TestVolumeKind> kinds;
    for (const std::string& name : volume_names) {
        bool found = false;
        for (auto kind : {bench::TestVolumeKind::sphere, bench::TestVolumeKind::shepp_logan,
                          bench::TestVolumeKind::slanted_interface})
            if (bench::testVolumeName(kind) == name) kinds.push_back(kind), found = true;
        if (!found) {
            std::fprintf(stderr, "ddtup-bench-volume: unknown volume %s\n", name.c_str());
            return 2;
        }
    }
    std::filesystem::create_directories(out);
    std::unique_ptr<ddt::VulkanContext> context;
    if (vulkan) {
        context = ddt::createContext({});
        std::printf("Vulkan device: %s\n", context->info.name.c_str());
        // The first use of each kernel compiles it (lavapipe: up to a second); not a row's time.
        magnifyByDdt("warm-up", bench::makeTestVolume(bench::TestVolumeKind::sphere, {8, 8, 8}), {8, 8, 8},
                     ddt::TetWeight::face_scf, context.get());
    }

    std::ostringstream table, csv;
    table << "| volume | noise σ | size | ÷ | method | PSNR dB | surface distance (voxels) | flips | optimize s | resample s |\n"
          << "|---|---:|---:|---:|---|---:|---:|---:|---:|---:|\n";
    csv << "volume,noise,size,factor,method,psnr_db,surface_distance,flips,optimize_s,resample_s\n";
    for (bench::TestVolumeKind kind : kinds)
        for (double noise : noises)
            for (uint32_t n : sizes) {
                const std::array<uint32_t, 3> size = {n, n, n};
                const ddt::Volume clean = bench::makeTestVolume(kind, size);
                const ddt::Volume original = noise > 0.0 ? bench::makeTestVolume(kind, size, noise, 7) : clean;
                const double range = bench::dataRange(clean);
                for (uint32_t factor : {2u, 4u}) {
                    if (factor == 4 && n < 64) continue;
                    const ddt::Volume small = bench::areaAverageVolume(original, factor);
                    std::vector<Method> methods;
                    methods.push_back(magnifyByGrid("trilinear", small, size, bench::GridFilter::trilinear));
                    methods.push_back(magnifyByGrid("tricubic (Catmull–Rom)", small, size, bench::GridFilter::catmull_rom));
                    methods.push_back(magnifyByKuhnMesh(small, size));
                    methods.push_back(magnifyByDdt("DDT, variance", small, size, ddt::TetWeight::variance));
                    methods.push_back(magnifyByDdt("DDT, face-SCF", small, size, ddt::TetWeight::face_scf));
                    if (context) {
                        methods.push_back(
                            magnifyByDdt("DDT, variance, Vulkan", small, size, ddt::TetWeight::variance, context.get()));
                        methods.push_back(
                            magnifyByDdt("DDT, face-SCF, Vulkan", small, size, ddt::TetWeight::face_scf, context.get()));
                    }
                    for (const Method& m : methods) {
                        const double psnr = bench::volumePsnr(clean, m.result, range);
                        const double distance = bench::isosurfaceDistance(clean, m.result, surfaceLevel(kind) * range);
                        char row[512];
                        std::snprintf(row, sizeof row, "| %s | %.2f | %u³ | %u | %s | %.2f | %.3f | %llu | %.3f | %.3f |\n",
                                      bench::testVolumeName(kind).c_str(), noise, n, factor, m.name.c_str(), psnr, distance,
                                      static_cast<unsigned long long>(m.flips), m.optimize_s, m.resample_s);
                        table << row;
                        std::fputs(row, stdout);
                        std::fflush(stdout);
                        std::snprintf(row, sizeof row, "%s,%.2f,%u,%u,%s,%.4f,%.4f,%llu,%.4f,%.4f\n",
                                      bench::testVolumeName(kind).c_str(), noise, n, factor, m.name.c_str(), psnr, distance,
                                      static_cast<unsigned long long>(m.flips), m.optimize_s, m.resample_s);
                        csv << row;
                    }
                    // Crops at the size a person can see voxels in: the smallest side asked for, ÷2.
                    if (factor == 2 && n == sizes.front()) {
                        std::vector<const ddt::Volume*> shown = {&clean};
                        for (const Method& m : methods)
                            if (m.name != "Kuhn mesh, no flips" && m.name.find("Vulkan") == std::string::npos)
                            shown.push_back(&m.result);
                        char name[128];
                        std::snprintf(name, sizeof name, "/crops-%s-noise%.2f-%u.png", bench::testVolumeName(kind).c_str(),
                                      noise, n);
                        writeCrops(out + name, shown, std::max(1u, 256 / n));
                    }
                }
            }
    std::ofstream(out + "/volume-bench.md") << table.str();
    std::ofstream(out + "/volume-bench.csv") << csv.str();
    return 0;
}
