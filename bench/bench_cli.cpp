#include "bench_cli.h"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

#include "low_res_protocols.h"

namespace bench {

namespace {

// --quick: small enough for every CI run, yet every stage of the full bench runs once.
void applyQuickDefaults(const CLI::App& app, BenchOptions& options) {
    if (!app.count("--factor")) options.factors = {4};
    if (!app.count("--repeats")) options.repeats = 1;
    if (!app.count("--scaling-max")) options.scaling_max_side = 128;
    if (!app.count("--scaling-repeats")) options.scaling_repeats = 1;
}

bool isPowerOfTwo(uint32_t n) { return n != 0 && (n & (n - 1)) == 0; }

}  // namespace

std::optional<BenchOptions> parseBenchCommandLine(int argc, char** argv, int& exit_code) {
    BenchOptions options;
    CLI::App app{"ddtup-bench: reproduces the paper's Tables 1-3 and Fig. 13 (see bench/README.md)", "ddtup-bench"};
    app.add_option("--data", options.data_dirs,
                   "Folder of images, one set per folder; repeatable (default: the bundled real and artificial sets)");
    app.add_option("--out", options.out_dir, "Folder for the report, tables, plots, crops and raw measurements")
        ->capture_default_str();
    app.add_option("--factor", options.factors, "Magnification factors, powers of two (default: 4 8; --quick: 4)");
    app.add_option("--warmup", options.warmups, "Untimed runs of each DDT method before the timed ones")
        ->capture_default_str();
    app.add_option("--repeats", options.repeats,
                   "Timed runs per DDT method and image; the median is reported (--quick: 1)")
        ->capture_default_str();
    app.add_option("--device", options.device, "Vulkan devices for the GPU columns: all, or one device id")
        ->capture_default_str();
    app.add_option("--scaling-image", options.scaling_image,
                   "Image resized to every size of Fig. 13 (default: the first image of the first set)");
    app.add_option("--scaling-max", options.scaling_max_side, "Largest side of Fig. 13's resized image (--quick: 128)")
        ->capture_default_str();
    app.add_option("--scaling-repeats", options.scaling_repeats, "Timed runs per size in Fig. 13 (--quick: 1)")
        ->capture_default_str();
    app.add_option("--tables", options.tables,
                   "Which tables: paper (Tables 1-3 and Fig. 13), protocols (protocols A, B, JPEG, bicubic and "
                   "camera at x2 to x8 with the peers and consistent DDT under each assumed filter), or all")
        ->check(CLI::IsMember({"paper", "protocols", "all"}))
        ->capture_default_str();
    app.add_option("--protocol-filter", options.protocol_filter,
                   "Adds protocol C to the protocol tables: one OIIO resize with this filter (e.g. mitchell, lanczos3)");
    app.add_option("--columns", options.columns,
                   "Only these columns of the protocol tables, by key (e.g. cpu+consistent+fallback, the default "
                   "run), with Lanczos3 always: minutes instead of hours when choosing a parameter")
        ->delimiter(',');
    app.add_flag("--quick", options.quick,
                 "Two small crops, factor 4, one repeat, Fig. 13 up to 128 px: checks that the bench still runs");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& error) {
        exit_code = app.exit(error);
        return std::nullopt;
    }

    auto usage = [&](const std::string& message) {
        std::cerr << "ddtup-bench: " << message << "\n";
        exit_code = 2;
        return std::nullopt;
    };
    if (options.quick) applyQuickDefaults(app, options);
    if (options.data_dirs.empty()) options.data_dirs = {DDTUP_BENCH_DATA "/real", DDTUP_BENCH_DATA "/artificial"};
    for (const std::string& dir : options.data_dirs)
        if (!std::filesystem::is_directory(dir)) return usage("--data " + dir + ": not a folder");
    if (!options.scaling_image.empty() && !std::filesystem::is_regular_file(options.scaling_image))
        return usage("--scaling-image " + options.scaling_image + ": no such file");
    if (options.factors.empty()) return usage("--factor needs at least one factor");
    for (uint32_t factor : options.factors)
        if (factor < 2 || factor > 64 || !isPowerOfTwo(factor))
            return usage("--factor must be a power of two from 2 to 64 (got " + std::to_string(factor) + ")");
    if (!options.protocol_filter.empty() && !isOiioFilter(options.protocol_filter))
        return usage("--protocol-filter " + options.protocol_filter + ": not an OIIO filter name");
    if (options.repeats == 0) return usage("--repeats must be at least 1");
    if (options.scaling_repeats == 0) return usage("--scaling-repeats must be at least 1");
    if (options.scaling_max_side < 64) return usage("--scaling-max must be at least 64");
    if (options.out_dir.empty()) return usage("--out must name a folder");
    return options;
}

}  // namespace bench
