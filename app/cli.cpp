#include "cli.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <iostream>

namespace ddt {

std::optional<Settings> parseCommandLine(int argc, char** argv, int& exit_code) {
    Settings settings;
    CLI::App app{"ddtup: image magnification by data-dependent triangulation", "ddtup"};
    app.set_version_flag("--version", std::string("ddtup ") + DDTUP_VERSION);
    app.add_option("input", settings.input, "Image to magnify (any format OpenImageIO reads)")->required();
    app.add_option("output", settings.output, "Where to write the result; the extension picks the format")->required();
    app.add_option("-s,--scale", settings.scale, "Magnification factor, a real number >= 1 (2 when no --width/--height)");
    app.add_option("--width", settings.width, "Output width in pixels; the height keeps the aspect unless --height is given");
    app.add_option("--height", settings.height, "Output height in pixels; the width keeps the aspect unless --width is given");
    app.add_option("--backend", settings.backend, "Optimizer: cpu (the serial reference)")
        ->check(CLI::IsMember({"cpu"}))
        ->capture_default_str();
    app.add_flag("--stats", settings.stats, "Print cost, flips and stage times");
    app.add_flag("-q,--quiet", settings.quiet, "Print nothing but errors");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& error) {
        exit_code = app.exit(error);
        return std::nullopt;
    }

    auto usage = [&](const std::string& message) {
        std::cerr << "ddtup: " << message << "\n";
        exit_code = 2;
        return std::nullopt;
    };
    const bool scale_given = app.count("--scale") > 0;
    if (scale_given && (std::isnan(settings.scale) || settings.scale < 1.0 || std::isinf(settings.scale)))
        return usage("--scale must be a number >= 1 (got " + app.get_option("--scale")->as<std::string>() + ")");
    if (scale_given && (settings.width || settings.height)) return usage("give either --scale or --width/--height, not both");
    if (app.count("--width") && settings.width == 0) return usage("--width must be at least 1");
    if (app.count("--height") && settings.height == 0) return usage("--height must be at least 1");
    if (!scale_given && !settings.width && !settings.height) settings.scale = 2.0;
    return settings;
}

}  // namespace ddt
