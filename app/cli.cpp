#include "cli.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <iostream>

#include "flip_rule.h"

namespace ddt {

std::optional<Settings> parseCommandLine(int argc, char** argv, int& exit_code) {
    Settings settings;
    CLI::App app{"ddtup: image magnification by data-dependent triangulation", "ddtup"};
    app.set_version_flag("--version", std::string("ddtup ") + DDTUP_VERSION);
    auto* input = app.add_option("input", settings.input, "Image to magnify (any format OpenImageIO reads)");
    auto* output = app.add_option("output", settings.output, "Where to write the result; the extension picks the format");
    app.add_option("-s,--scale", settings.scale, "Magnification factor, a real number >= 1 (2 when no --width/--height)");
    app.add_option("--width", settings.width, "Output width in pixels; the height keeps the aspect unless --height is given");
    app.add_option("--height", settings.height, "Output height in pixels; the width keeps the aspect unless --width is given");
    app.add_option("--backend", settings.backend, "Optimizer: vulkan (parallel flips on the GPU) or cpu (the serial reference)")
        ->check(CLI::IsMember({"vulkan", "cpu"}))
        ->capture_default_str();
    app.add_option("--variant", settings.variant,
                   std::string("Vulkan flip rule: basic, exproi, exproi-N-maxgain, maxgain, exproi-maxgain, localmax, "
                               "exproi-localmax (default ") + kDefaultFlipRule + ")");
    app.add_option("--device", settings.device, "Vulkan device index from --list-devices (default: the first discrete GPU, "
                                                "then integrated, then CPU devices)");
    app.add_flag("--list-devices", settings.list_devices, "List the Vulkan devices and exit");
    app.add_flag("!--no-active-set", settings.active_set,
                 "Vulkan: re-test every edge in every iteration instead of only those a flip may have changed");
    app.add_flag("--stats", settings.stats, "Print cost, flips and stage times");
    app.add_flag("-q,--quiet", settings.quiet, "Print nothing but errors");
    // The image arguments are required unless only listing devices.
    input->required();
    output->required();
    for (int i = 1; i < argc; ++i)
        if (std::string(argv[i]) == "--list-devices") input->required(false), output->required(false);
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
    if (!settings.variant.empty() && !parseFlipRule(settings.variant))
        return usage("--variant " + settings.variant + ": unknown flip rule (see --help)");
    if (!settings.variant.empty() && settings.backend != "vulkan") return usage("--variant needs --backend vulkan");
    return settings;
}

}  // namespace ddt
