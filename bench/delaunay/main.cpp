// ddtup-bench-delaunay: the bench of scattered samples (bench/README.md), two tables.
//  1. Delaunay: ddtup's serial triangulation of points (core/delaunay/) and, with --vulkan, its
//     device triangulation (compute/delaunay/) against CGAL's Delaunay_triangulation_2 — time,
//     peak memory, checks — on uniform, clustered, grid and circle point sets of 10^4 points
//     up to --max-points.
//  2. Reconstruction: each bundled image rebuilt from some of its pixels (random 5, 10, 20 %,
//     or all but random discs) by linear interpolation on the Delaunay mesh, by DDT on it, by
//     CGAL's natural neighbours and, for the discs, by G'MIC's inpainting; PSNR against the
//     full image, over all pixels and over the unknown ones.
// Markdown tables on stdout, progress on stderr, --json FILE for the raw numbers.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "delaunay.h"
#include "gmic_peer.h"
#include "image_file.h"
#include "json_writer.h"
#include "point_sets.h"
#include "reconstruction.h"
#include "sample_patterns.h"
#include "triangulation_table.h"
#include "vulkan_backend.h"

namespace fs = std::filesystem;

namespace {

struct Settings {
    uint64_t max_points = 1'000'000;
    bool quick = false;
    std::string json;
    std::string pictures;  // --pictures DIR
    std::string data = DDTUP_BENCH_DATA;
    std::vector<std::string> images;  // names without extension; empty: all
    uint32_t max_side = 0;            // centred crop to at most this side; 0: whole images
    uint32_t repeats = 3;
    uint32_t timeout_s = 600;
    uint64_t seed = 1;
    std::string tables = "all";
    std::vector<std::string> sets = {"uniform", "gaussians", "grid", "circle", "exact-circle"};
    bool vulkan = false;
};

struct ImageRun {
    std::string set, name, pattern;
    uint32_t width = 0, height = 0;
    double known_share = 0.0;
    std::vector<bench::Reconstruction> rows;
};

std::string mib(uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", double(bytes) / (1 << 20));
    return text;
}

std::string fixed(double value, int digits) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*f", digits, value);
    return text;
}

// ---- Table 1 ----

std::vector<bench::TriangulationRow> runDelaunayTable(const Settings& s) {
    std::vector<uint64_t> sizes;
    for (uint64_t n = 10'000; n <= s.max_points; n *= 10) sizes.push_back(n);
    std::vector<bench::TriangulationRow> rows;
    auto run = [&](bench::PointSetKind kind, uint64_t n) {
        const bench::PointSet set = bench::makePointSet(kind, n, s.seed);
        // A single run where one already takes seconds: the median of 3 adds little there.
        const uint32_t repeats = set.points.size() >= 5'000'000 ? 1 : s.repeats;
        std::fprintf(stderr, "delaunay: %s, %zu points …\n", set.name.c_str(), set.points.size());
        rows.push_back(bench::measureTriangulations(set, repeats, s.timeout_s, s.vulkan));
    };
    auto wanted = [&](const char* name) { return std::find(s.sets.begin(), s.sets.end(), name) != s.sets.end(); };
    const std::pair<const char*, bench::PointSetKind> kinds[] = {{"uniform", bench::PointSetKind::uniform},
                                                                 {"gaussians", bench::PointSetKind::gaussian},
                                                                 {"grid", bench::PointSetKind::grid},
                                                                 {"circle", bench::PointSetKind::circle}};
    for (const auto& [name, kind] : kinds)
        if (wanted(name))
            for (uint64_t n : sizes) run(kind, n);
    if (wanted("exact-circle")) run(bench::PointSetKind::exact_circle, 0);
    return rows;
}

std::string cell(const std::string& failure, const std::string& value) { return failure.empty() ? value : failure; }

// The Vulkan columns of a row: wall s, its ratio to CGAL's wall time, flips a point and the
// stages, peak MiB, edges vs serial.
std::string vulkanCells(const bench::TriangulationRow& r) {
    if (!r.vulkan_measured) return "— | — | — | — | —";
    if (!r.vulkan_failure.empty()) return r.vulkan_failure + " | — | — | — | —";
    const std::string ratio = r.cgal_failure.empty() ? fixed(r.vulkan_wall_s / r.cgal_wall_s, 2) : "—";
    const std::string stages = fixed(double(r.vulkan_flips) / double(r.points), 2) + "; " +
                               fixed(r.vulkan_sweep_s, 3) + " / " + fixed(r.vulkan_device_s, 3) + " / " +
                               fixed(r.vulkan_number_s, 3);
    return fixed(r.vulkan_wall_s, 4) + " (" + std::to_string(r.vulkan_rounds) + " rounds) | " + ratio + " | " +
           stages + " | " + mib(r.vulkan_bytes) + " | " + r.vulkan_comparison;
}

// The load average, for the notes: on a shared machine the wall-clock times grow with it.
std::string loadAverage() {
    double load[3] = {0, 0, 0};
    getloadavg(load, 3);
    return fixed(load[0], 2) + " (1 min), " + fixed(load[2], 2) + " (15 min)";
}

void printDelaunayTable(const std::vector<bench::TriangulationRow>& rows, const std::string& load) {
    std::printf("\n### Delaunay triangulation: ddtup (serial) against CGAL\n\n");
    std::printf("| set | points | ddtup CPU s | CGAL CPU s | CPU ddtup/CGAL | ddtup wall s | CGAL wall s | ddtup peak MiB "
                "| CGAL peak MiB | memory ddtup/CGAL | triangles | ddtup checks | CGAL is_valid | edges vs CGAL "
                "| Vulkan wall s | wall Vulkan/CGAL | Vulkan flips a point; sweep / device / numbering s "
                "| Vulkan peak MiB | Vulkan edges vs serial |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|---:|---:|---:|---:|---|\n");
    for (const auto& r : rows) {
        const bool both = r.ddtup_failure.empty() && r.cgal_failure.empty();
        const std::string triangles = !r.ddtup_failure.empty() ? std::to_string(r.cgal_triangles)
                                      : (r.cgal_failure.empty() && r.ddtup_triangles != r.cgal_triangles)
                                          ? std::to_string(r.ddtup_triangles) + " vs " + std::to_string(r.cgal_triangles)
                                          : std::to_string(r.ddtup_triangles);
        std::printf("| %s | %llu | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", r.set.c_str(),
                    (unsigned long long)r.points, cell(r.ddtup_failure, fixed(r.ddtup_s, 4)).c_str(),
                    cell(r.cgal_failure, fixed(r.cgal_s, 4)).c_str(), both ? fixed(r.ddtup_s / r.cgal_s, 2).c_str() : "—",
                    cell(r.ddtup_failure, fixed(r.ddtup_wall_s, 4)).c_str(),
                    cell(r.cgal_failure, fixed(r.cgal_wall_s, 4)).c_str(),
                    cell(r.ddtup_failure, mib(r.ddtup_bytes)).c_str(), cell(r.cgal_failure, mib(r.cgal_bytes)).c_str(),
                    both && r.cgal_bytes ? fixed(double(r.ddtup_bytes) / double(r.cgal_bytes), 2).c_str() : "—",
                    triangles.c_str(),
                    r.ddtup_failure.empty() ? (r.ddtup_check.empty() ? "pass" : r.ddtup_check.c_str()) : "—",
                    r.cgal_failure.empty() ? (r.cgal_valid ? "pass" : "FAIL") : "—", r.comparison.c_str(),
                    vulkanCells(r).c_str());
    }
    std::printf("\nTimes: median of the repeats (one run from 5·10^6 points), CPU time of the process and wall clock "
                "(load average %s); peak: the growth of the peak resident set over the first run, in a forked child "
                "per library (input excluded). ddtup checks: checkDelaunay and checkMesh(convex hull). edges vs CGAL: "
                "on the random sets, where the triangulation is unique. Vulkan (--vulkan): the device's Delaunay on the "
                "first Vulkan device — a serial sweep, then parallel flips on the device — wall clock of the whole call, "
                "the last run's flips a point and its stages (the CPU's sweep; the device's rounds with the uploads "
                "and downloads; the CPU's canonical numbering), its edges against the serial ones on every set (the "
                "same tie-break makes them equal).\n",
                load.c_str());
}

// ---- Table 2 ----

std::vector<std::pair<std::string, fs::path>> imagePaths(const Settings& s) {
    std::vector<std::pair<std::string, fs::path>> paths;
    for (const char* set : {"real", "artificial"}) {
        std::vector<fs::path> files;
        for (const auto& entry : fs::directory_iterator(fs::path(s.data) / set))
            if (entry.path().extension() == ".png") files.push_back(entry.path());
        std::sort(files.begin(), files.end());
        for (const fs::path& file : files) {
            const std::string name = file.stem().string();
            if (s.images.empty() || std::find(s.images.begin(), s.images.end(), name) != s.images.end())
                paths.emplace_back(set, file);
        }
    }
    return paths;
}

// The centred crop of `image` to at most side × side pixels.
ddt::Image centredCrop(const ddt::Image& image, uint32_t side) {
    if (side == 0 || (image.width <= side && image.height <= side)) return image;
    ddt::Image crop = image;
    crop.width = std::min(image.width, side);
    crop.height = std::min(image.height, side);
    const uint32_t x0 = (image.width - crop.width) / 2, y0 = (image.height - crop.height) / 2;
    crop.pixels.resize(size_t(crop.width) * crop.height * image.channels);
    for (uint32_t y = 0; y < crop.height; ++y)
        std::copy_n(image.row(y0 + y) + size_t(x0) * image.channels, crop.rowFloats(), crop.row(y));
    return crop;
}

std::vector<ImageRun> runReconstructionTable(const Settings& s) {
    const std::vector<bench::SamplePattern> patterns = {
        {"random 5 %", 0.05, false}, {"random 10 %", 0.10, false}, {"random 20 %", 0.20, false}, {"blobs 15 %", 0.15, true}};
    std::unique_ptr<ddt::Backend> vulkan;
    if (s.vulkan) {
        vulkan = ddt::makeVulkanBackend({});
        // The first use of each kernel compiles it (lavapipe: up to a second); not a row's time.
        ddt::Image warm_up;
        warm_up.width = warm_up.height = 8;
        warm_up.channels = 1;
        for (uint32_t v = 0; v < 64; ++v) warm_up.pixels.push_back(float((v * 37) % 11) / 10.0f);
        vulkan->prepareFrom(warm_up, ddt::delaunayOfPixels(8, 8, {0, 7, 10, 19, 28, 37, 45, 56, 63}));
        vulkan->optimize();
    }
    bench::ReconstructionOptions options;
    options.vulkan = vulkan.get();
    std::vector<ImageRun> runs;
    uint64_t image_index = 0;
    for (const auto& [set, path] : imagePaths(s)) {
        const ddt::Image image = centredCrop(ddt::readImage(path.string()), s.max_side);
        for (size_t p = 0; p < patterns.size(); ++p) {
            ImageRun run;
            run.set = set;
            run.name = path.stem().string();
            run.pattern = patterns[p].name;
            run.width = image.width;
            run.height = image.height;
            const std::vector<uint32_t> known =
                bench::knownPixelsOf(patterns[p], image.width, image.height, s.seed * 1000003 + image_index * 16 + p);
            run.known_share = double(known.size()) / (double(image.width) * image.height);
            std::fprintf(stderr, "reconstruction: %s/%s %u×%u, %s …\n", set.c_str(), run.name.c_str(), image.width,
                         image.height, run.pattern.c_str());
            if (!s.pictures.empty()) {
                const std::string prefix = s.pictures + "/" + run.name + "-" + bench::slugOf(run.pattern) + "-";
                ddt::writeImage(prefix + "original.png", image);
                options.pictures = prefix;
            }
            run.rows = bench::reconstructAll(image, known, patterns[p].blobs, options);
            runs.push_back(std::move(run));
        }
        ++image_index;
    }
    return runs;
}

void printReconstructionTable(const std::vector<ImageRun>& runs, const std::string& load) {
    std::printf("\n### Reconstruction from samples: PSNR (dB) against the full image, means over the images\n\n");
    std::printf("| set | images | pattern | known %% | method | PSNR all | PSNR unknown | CPU s | wall s | flips |\n");
    std::printf("|---|---:|---|---:|---|---:|---:|---:|---:|---:|\n");
    // Groups (set, pattern): real before artificial, patterns in the order they ran; methods in
    // the order reconstructAll lists them.
    std::vector<std::pair<std::string, std::string>> groups;
    for (const ImageRun& run : runs)
        if (std::find(groups.begin(), groups.end(), std::pair(run.set, run.pattern)) == groups.end())
            groups.emplace_back(run.set, run.pattern);
    std::stable_sort(groups.begin(), groups.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
    for (const auto& [set, pattern] : groups) {
        std::vector<const ImageRun*> members;
        for (const ImageRun& run : runs)
            if (run.set == set && run.pattern == pattern) members.push_back(&run);
        double known = 0.0;
        for (const ImageRun* run : members) known += run->known_share;
        for (size_t m = 0; m < members.front()->rows.size(); ++m) {
            const std::string& method = members.front()->rows[m].method;
            double all = 0.0, unknown = 0.0, cpu = 0.0, seconds = 0.0, flips = 0.0;
            std::string failure;
            for (const ImageRun* run : members) {
                const bench::Reconstruction& r = run->rows[m];
                if (!r.failure.empty()) failure = r.failure;
                all += r.psnr_all, unknown += r.psnr_unknown, cpu += r.cpu_seconds, seconds += r.seconds;
                flips += double(r.flips);
            }
            const double n = double(members.size());
            std::printf("| %s | %zu | %s | %.1f | %s | %s | %s | %s | %s | %s |\n", set.c_str(), members.size(),
                        pattern.c_str(), 100.0 * known / n, method.c_str(), cell(failure, fixed(all / n, 2)).c_str(),
                        cell(failure, fixed(unknown / n, 2)).c_str(), cell(failure, fixed(cpu / n, 3)).c_str(),
                        cell(failure, fixed(seconds / n, 3)).c_str(),
                        method.rfind("DDT", 0) == 0 ? fixed(flips / n, 0).c_str() : "—");
        }
    }
    std::printf("\nKnown pixels: the pattern's plus the 4 corners (so the hull is the frame). PSNR: 8-bit colour "
                "values (core/metrics.h), mean of per-image dB. Times: mean per image, from the known pixels to the "
                "image (Delaunay and rendering included; G'MIC: its process, PNG files included); CPU: all threads "
                "(load average %s).\n", load.c_str());
}

// ---- JSON ----

void writeJson(const std::string& path, const std::vector<bench::TriangulationRow>& delaunay,
               const std::vector<ImageRun>& runs, const Settings& s) {
    bench::JsonWriter json;
    json.beginObject();
    json.key("max_points").value(uint64_t(s.max_points)).key("quick").value(s.quick).key("seed").value(uint64_t(s.seed));
    json.key("delaunay").beginArray();
    for (const auto& r : delaunay) {
        json.beginObject()
            .key("set").value(r.set)
            .key("points").value(uint64_t(r.points))
            .key("ddtup_failure").value(r.ddtup_failure)
            .key("cgal_failure").value(r.cgal_failure)
            .key("ddtup_s").value(r.ddtup_s)
            .key("cgal_s").value(r.cgal_s)
            .key("ddtup_wall_s").value(r.ddtup_wall_s)
            .key("cgal_wall_s").value(r.cgal_wall_s)
            .key("ddtup_peak_bytes").value(uint64_t(r.ddtup_bytes))
            .key("cgal_peak_bytes").value(uint64_t(r.cgal_bytes))
            .key("ddtup_triangles").value(uint64_t(r.ddtup_triangles))
            .key("cgal_triangles").value(uint64_t(r.cgal_triangles))
            .key("ddtup_check").value(r.ddtup_check)
            .key("cgal_valid").value(r.cgal_valid)
            .key("comparison").value(r.comparison)
            .key("vulkan_measured").value(r.vulkan_measured)
            .key("vulkan_failure").value(r.vulkan_failure)
            .key("vulkan_wall_seconds").value(r.vulkan_wall_s)
            .key("vulkan_peak_bytes").value(r.vulkan_bytes)
            .key("vulkan_rounds").value(r.vulkan_rounds)
            .key("vulkan_flips").value(uint64_t(r.vulkan_flips))
            .key("vulkan_sweep_seconds").value(r.vulkan_sweep_s)
            .key("vulkan_device_seconds").value(r.vulkan_device_s)
            .key("vulkan_number_seconds").value(r.vulkan_number_s)
            .key("vulkan_comparison").value(r.vulkan_comparison)
            .endObject();
    }
    json.endArray();
    json.key("reconstruction").beginArray();
    for (const ImageRun& run : runs) {
        json.beginObject()
            .key("set").value(run.set)
            .key("image").value(run.name)
            .key("width").value(run.width)
            .key("height").value(run.height)
            .key("pattern").value(run.pattern)
            .key("known_share").value(run.known_share);
        json.key("methods").beginArray();
        for (const bench::Reconstruction& r : run.rows)
            json.beginObject()
                .key("method").value(r.method)
                .key("failure").value(r.failure)
                .key("seconds").value(r.seconds)
                .key("cpu_seconds").value(r.cpu_seconds)
                .key("flips").value(uint64_t(r.flips))
                .key("psnr_all").value(r.psnr_all)
                .key("psnr_unknown").value(r.psnr_unknown)
                .endObject();
        json.endArray().endObject();
    }
    json.endArray().endObject();
    std::ofstream(path) << json.text() << "\n";
}

int run(const Settings& s) {
    std::vector<bench::TriangulationRow> delaunay;
    std::vector<ImageRun> runs;
    std::string delaunay_load, reconstruction_load;
    if (s.tables != "reconstruction") {
        delaunay = runDelaunayTable(s);
        delaunay_load = loadAverage();
    }
    if (s.tables != "delaunay") {
        runs = runReconstructionTable(s);
        reconstruction_load = loadAverage();
    }
    if (!delaunay.empty()) printDelaunayTable(delaunay, delaunay_load);
    if (!runs.empty()) printReconstructionTable(runs, reconstruction_load);
    if (!s.json.empty()) writeJson(s.json, delaunay, runs, s);
    // A check that failed fails the run, so that CI's quick run (bench/CMakeLists.txt) tests them.
    int status = 0;
    for (const bench::TriangulationRow& row : delaunay) {
        if (row.comparison != "equal" && row.comparison != "both valid") {
            std::fprintf(stderr, "ddtup-bench-delaunay: %s, %llu points: %s (ddtup: %s; CGAL valid: %s)\n",
                         row.set.c_str(), static_cast<unsigned long long>(row.points), row.comparison.c_str(),
                         row.ddtup_check.empty() ? "pass" : row.ddtup_check.c_str(), row.cgal_valid ? "yes" : "no");
            status = 1;
        }
        if (row.vulkan_measured && row.vulkan_comparison != "equal") {
            std::fprintf(stderr, "ddtup-bench-delaunay: %s, %llu points: Vulkan %s\n", row.set.c_str(),
                         static_cast<unsigned long long>(row.points),
                         row.vulkan_failure.empty() ? row.vulkan_comparison.c_str() : row.vulkan_failure.c_str());
            status = 1;
        }
    }
    return status;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"ddtup-bench-delaunay: Delaunay of points against CGAL, and reconstruction from samples"};
    Settings s;
    app.add_option("--max-points", s.max_points, "Largest point set of the Delaunay table (10^4, 10^5 … up to this)")
        ->capture_default_str()->check(CLI::Range(uint64_t(10'000), uint64_t(100'000'000)));
    app.add_flag("--quick", s.quick, "10^4 and 10^5 points, one run each; two images cropped to 256²: CI's check that the bench runs");
    app.add_option("--sets", s.sets, "Point sets of the Delaunay table")
        ->delimiter(',')->capture_default_str()->check(CLI::IsMember({"uniform", "gaussians", "grid", "circle", "exact-circle"}));
    app.add_option("--json", s.json, "Also write every measurement to this file");
    app.add_option("--pictures", s.pictures,
                   "Also write every reconstruction as a PNG into this folder (it must exist): "
                   "IMAGE-PATTERN-METHOD.png, with IMAGE-PATTERN-original.png and -known.png");
    app.add_option("--data", s.data, "Folder with real/ and artificial/ PNG images")->capture_default_str();
    app.add_option("--images", s.images, "Only these images (names without .png)")->delimiter(',');
    app.add_option("--max-side", s.max_side, "Crop each image (centred) to at most this side; 0: whole")->capture_default_str();
    app.add_option("--repeats", s.repeats, "Timed runs per triangulation (the median is shown)")
        ->capture_default_str()->check(CLI::Range(1, 100));
    app.add_option("--timeout", s.timeout_s, "Seconds a triangulation may take before it is killed")->capture_default_str();
    app.add_option("--seed", s.seed, "Seed of the point sets and sample patterns")->capture_default_str();
    app.add_option("--tables", s.tables, "all, delaunay or reconstruction")
        ->capture_default_str()->check(CLI::IsMember({"all", "delaunay", "reconstruction"}));
    app.add_flag("--vulkan", s.vulkan,
                 "Also the Delaunay triangulation and DDT on the first Vulkan device (the Vulkan columns; a row "
                 "\"DDT, sederberg, Vulkan\")");
    CLI11_PARSE(app, argc, argv);
    if (s.quick) {
        s.max_points = std::min<uint64_t>(s.max_points, 100'000);
        if (s.images.empty()) s.images = {"astronaut", "monkey"};
        if (s.max_side == 0) s.max_side = 256;
        s.repeats = 1;  // a check that the bench runs, not a measurement
    }
    if (!fs::is_directory(fs::path(s.data) / "real")) {
        std::fprintf(stderr, "ddtup-bench-delaunay: %s: no real/ folder of images\n", s.data.c_str());
        return 2;
    }
    try {
        return run(s);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "ddtup-bench-delaunay: %s\n", error.what());
        return 1;
    }
}
