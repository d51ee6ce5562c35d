#include "cli.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <iostream>

#include "flip_rule.h"

namespace ddt {

namespace {

// Usage errors share one exit code, whichever layer finds them (README: 2).
const int kUsageExitCode = 2;

// "" if the parsed values make sense together, else the message.
std::string validateSettings(const CLI::App& app, const Settings& settings) {
    const bool scale_given = app.count("--scale") > 0;
    if (scale_given && !(settings.scale >= 1.0 && std::isfinite(settings.scale)))
        return "--scale must be a number >= 1 (got " + app.get_option("--scale")->as<std::string>() + ")";
    if (scale_given && (settings.width || settings.height)) return "give either --scale or --width/--height, not both";
    if (app.count("--width") && settings.width == 0) return "--width must be at least 1";
    if (app.count("--height") && settings.height == 0) return "--height must be at least 1";
    if (!settings.variant.empty() && !parseFlipRule(settings.variant))
        return "--variant " + settings.variant + ": unknown flip rule (see --help)";
    if (!settings.variant.empty() && settings.backend != "vulkan") return "--variant needs --backend vulkan";
    return "";
}

// CLI11 messages are one line today; keep it that way whatever it says.
std::string oneLine(std::string message) {
    for (char& c : message)
        if (c == '\n') c = ' ';
    return message;
}

}  // namespace

std::optional<Settings> parseCommandLine(int argc, char** argv, int& exit_code) {
    Settings settings;
    CLI::App app{"ddtup: image magnification by data-dependent triangulation", "ddtup"};
    app.set_version_flag("--version", std::string("ddtup ") + DDTUP_VERSION);
    auto* input = app.add_option("input", settings.input, "Image to magnify (any format OpenImageIO reads)");
    auto* output = app.add_option("output", settings.output, "Where to write the result; the extension picks the format");
    app.add_option("-s,--scale", settings.scale, "Magnification factor, a real number >= 1 (used when no --width/--height)")
        ->default_str("2");
    app.add_option("--width", settings.width,
                   "Output width in pixels; the height keeps the aspect unless --height is given (default: from --scale)");
    app.add_option("--height", settings.height,
                   "Output height in pixels; the width keeps the aspect unless --width is given (default: from --scale)");
    app.add_option("--backend", settings.backend, "Optimizer: vulkan (parallel flips on the GPU) or cpu (the serial reference)")
        ->check(CLI::IsMember({"vulkan", "cpu"}))
        ->capture_default_str();
    app.add_option("--variant", settings.variant,
                   "Vulkan flip rule: basic, exproi, exproi-N-maxgain, maxgain, exproi-maxgain, localmax, exproi-localmax")
        ->default_str(kDefaultFlipRule);
    app.add_option("--device", settings.device, "Vulkan device index from --list-devices")
        ->default_str("the first discrete GPU, then integrated, then CPU devices");
    app.add_flag("--list-devices", settings.list_devices, "List the Vulkan devices and exit");
    app.add_flag("!--no-active-set", settings.active_set,
                 "Vulkan: re-test every edge in every iteration, not only those a flip may have changed (default: off)");
    app.add_flag("--stats", settings.stats, "Print cost, flips and stage times (default: off)");
    app.add_flag("-q,--quiet", settings.quiet, "Print nothing but errors (default: off)");
    // The image arguments are required unless only listing devices.
    input->required();
    output->required();
    for (int i = 1; i < argc; ++i)
        if (std::string(argv[i]) == "--list-devices") input->required(false), output->required(false);

    auto usageError = [&](const std::string& message) {
        std::cerr << "ddtup: " << oneLine(message) << "\n";
        exit_code = kUsageExitCode;
        return std::nullopt;
    };
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& error) {
        // --help and --version arrive here too, with exit code 0; CLI11 prints them.
        if (error.get_exit_code() == 0) {
            exit_code = app.exit(error);
            return std::nullopt;
        }
        return usageError(error.what());
    }
    if (std::string problem = validateSettings(app, settings); !problem.empty()) return usageError(problem);
    if (!app.count("--scale") && !settings.width && !settings.height) settings.scale = 2.0;
    return settings;
}

}  // namespace ddt
