#include "cli.h"

#include <CLI/CLI.hpp>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iostream>

#include "assumed_kernel.h"
#include "batch_plan.h"
#include "exit_codes.h"
#include "cost.h"
#include "delaunay.h"
#include "flip_rule.h"
#include "image.h"
#include "image_formats.h"
#include "json_line.h"
#include "mesh_file.h"
#include "point_file.h"
#include "tiled_upscale.h"
#include "volume_file.h"

namespace ddt {

namespace {

const char* const kDescription =
    "ddtup: image magnification by data-dependent triangulation\n"
    "\n"
    "  ddtup IN OUT [options]              one image (IN or OUT may be - for standard input/output)\n"
    "  ddtup IN... -o DIR [options]        several images into the folder DIR\n"
    "  ddtup IN... DIR/ [options]          the same, when DIR exists or ends in /\n"
    "  ddtup -i DIR -o DIR [-r] [options]  a folder of images (-r: and its sub-folders) into a folder\n"
    "\n"
    "Volumes (.nrrd, .nhdr, .nii, .nii.gz: scalar 8/16-bit, float, double) are magnified by a data-dependent\n"
    "tetrahedralization in any of these forms; -s FX,FY,FZ gives a factor per axis.\n"
    "\n"
    "Examples:\n"
    "  ddtup photo.png -s 4 photo-x4.png\n"
    "  ddtup *.jpg -o big/ --width 3840 -f png\n"
    "  ddtup -i scans -o scans-x2 -r --skip-existing --progress=json\n"
    "  ddtup ct.nii.gz -s 2,2,5 ct-fine.nii.gz --slices views/\n"
    "\n"
    "Exit codes: 0 all done, 1 some images failed, 2 bad usage, 3 no usable Vulkan device,\n"
    "4 internal error, 130/143 interrupted.";

// "" if --mesh and --mesh-height make sense with the rest, else the message.
std::string validateMesh(const CLI::App& app, const Settings& settings) {
    if (app.count("--simplify") && !(settings.simplify > 0.0 && settings.simplify <= 1.0))
        return "--simplify must be a fraction in (0, 1] (got " + app.get_option("--simplify")->as<std::string>() + ")";
    if (app.count("--max-error") && !(settings.max_error > 0.0 && std::isfinite(settings.max_error)))
        return "--max-error must be a positive number of 8-bit levels (got " + app.get_option("--max-error")->as<std::string>() + ")";
    if (settings.simplifies() && app.count("--reconstruct") && settings.reconstruct == "consistent")
        return "simplification (--simplify, --max-error) renders the linear surface on the simplified mesh; --reconstruct "
               "consistent does not apply";
    if (app.count("--mesh-height") && settings.mesh.empty()) return "--mesh-height needs --mesh";
    if (!std::isfinite(settings.mesh_height)) return "--mesh-height must be a finite number";
    if (settings.mesh.empty()) return "";
    if (!settings.singleForm()) {
        // In the batch forms each mesh goes beside its output: only the format is given.
        const std::string name = settings.mesh.starts_with('.') ? settings.mesh.substr(1) : settings.mesh;
        if (name.find('.') != std::string::npos || name.find('/') != std::string::npos || !meshFormatOf(name))
            return "--mesh " + settings.mesh + ": in the batch forms give a format, " + meshFormatNames() +
                   " (each mesh goes beside its output, named like it)";
        return "";
    }
    if (!std::filesystem::path(settings.mesh).has_extension() || !meshFormatOf(settings.mesh))
        return "--mesh " + settings.mesh + ": unknown mesh format (the extension must name " + meshFormatNames() + ")";
    for (const std::string& input : settings.inputs)
        if (input != kStandardStream && sameFile(input, settings.mesh))
            return "--mesh " + settings.mesh + ": is the input; refusing to overwrite it";
    if (settings.output != kStandardStream && sameFile(settings.output, settings.mesh))
        return "--mesh " + settings.mesh + ": is also the image's output";
    return "";
}

// "" if --mask or --mask-dir makes sense with the rest, else the message.
std::string validateMask(const CLI::App& app, const Settings& settings) {
    if (!settings.masked()) return "";
    if (!settings.mask.empty() && !settings.mask_folder.empty())
        return "--mask gives one image's mask, --mask-dir a batch's: give one of them";
    const std::string option = settings.mask.empty() ? "--mask-dir" : "--mask";
    if (app.count("--reconstruct") && settings.reconstruct == "consistent")
        return option + " renders the linear surface on the known pixels' triangulation; --reconstruct consistent needs "
               "every pixel's value";
    if (settings.tile && !settings.mesh.empty())
        return option + " with --mesh writes the whole triangulation of the known pixels; --tile does not apply";
    if (settings.tile && settings.simplifies())
        return option + " with simplification (--simplify, --max-error) simplifies the known pixels' triangulation in one "
               "piece; --tile does not apply";
    if (settings.mask.empty()) return "";
    if (!settings.singleForm() || settings.inputs.size() != 1)
        return "--mask pairs one mask with one input: `ddtup IN --mask MASK OUT`; a batch takes --mask-dir MASKS";
    if (sameFile(settings.mask, settings.inputs.front())) return "--mask " + settings.mask + ": is the input itself";
    if (settings.output != kStandardStream && sameFile(settings.mask, settings.output))
        return "--mask " + settings.mask + ": is also the output; refusing to overwrite it";
    return "";
}

// "" if --assume makes sense with the rest, else the message: only the consistent surface
// assumes a downscale filter.
std::string validateAssume(const CLI::App& app, const Settings& settings) {
    if (!app.count("--assume")) return "";
    const std::string given = "--assume " + settings.assume + ": ";
    if (settings.reconstruct != "consistent") return given + "only the consistent surface assumes a filter; --reconstruct plain does not";
    if (settings.simplifies()) return given + "simplification (--simplify, --max-error) renders the linear surface, which assumes no filter";
    if (settings.masked()) return given + "a mask renders the linear surface, which assumes no filter";
    if (std::any_of(settings.inputs.begin(), settings.inputs.end(), isPointFilePath))
        return given + "a point file is rendered linearly, which assumes no filter";
    return "";
}

// "" if --fallback makes sense with the rest, else the message: it blends the mesh's surface
// with a convolution of the full input.
std::string validateFallback(const Settings& settings) {
    if (settings.fallback != "lanczos3") return "";  // the default gives way with the consistent surface
    const std::string given = "--fallback " + settings.fallback + ": ";
    if (settings.simplifies()) return given + "simplification (--simplify, --max-error) renders its own mesh's surface";
    if (settings.masked()) return given + "a mask's unknown pixels have no input to convolve";
    if (std::any_of(settings.inputs.begin(), settings.inputs.end(), isPointFilePath))
        return given + "a point file has no pixel grid to convolve";
    return "";
}

// "" if --delaunay has samples to triangulate, else the message.
std::string validateDelaunay(const CLI::App& app, const Settings& settings) {
    if (!app.count("--delaunay") || settings.masked() || !settings.input_folder.empty()) return "";
    if (std::any_of(settings.inputs.begin(), settings.inputs.end(), isPointFilePath)) return "";
    return "--delaunay " + settings.delaunay + ": applies to masks and point files, whose samples are triangulated";
}

// "" if point-file inputs (core/io/point_file.h) make sense with the rest, else the message.
std::string validatePoints(const CLI::App& app, const Settings& settings) {
    const bool any_points = std::any_of(settings.inputs.begin(), settings.inputs.end(), isPointFilePath);
    if (!any_points) return app.count("--frame") ? "--frame applies to point files (.csv, .ply)" : "";
    if (settings.masked()) return "--mask and --mask-dir apply to images: a point file lists only known samples";
    if (app.count("--reconstruct") && settings.reconstruct == "consistent")
        return "a point file is rendered linearly on its triangulation; --reconstruct consistent needs a full image";
    if (settings.tile && !settings.mesh.empty())
        return "a point file with --mesh writes the whole triangulation of the points; --tile does not apply";
    if (settings.tile && settings.simplifies())
        return "a point file's simplification (--simplify, --max-error) takes the whole triangulation; --tile does not "
               "apply";
    if (settings.format.empty() && (!settings.singleForm() || settings.output == kStandardStream))
        return "a point file's output needs a format: name the output file, or give -f png";
    if (app.count("--frame") && (settings.frame_width > kMaxDelaunaySide || settings.frame_height > kMaxDelaunaySide))
        return "--frame: at most " + std::to_string(kMaxDelaunaySide) + " pixels a side (the exact in-circle test's range)";
    return "";
}

// --memory's size: a number of bytes with an optional K, M, G or T (powers of 1024, "MiB" and
// "MB" read alike), at least 16 MiB; "" if it parses, else the message.
std::string parseMemory(const std::string& text, Settings& settings) {
    const std::string bad = "--memory " + text + ": give a size such as 512M or 4G (at least 16M)";
    size_t end = 0;
    double number = 0.0;
    try {
        number = std::stod(text, &end);
    } catch (const std::exception&) {
        return bad;
    }
    std::string unit = text.substr(end);
    for (const char* suffix : {"iB", "B"})
        if (unit.size() > 1 && unit.ends_with(suffix)) unit.resize(unit.size() - std::strlen(suffix));
    const std::string units = "KMGT";
    const size_t power = unit.empty() ? 0 : units.find(char(std::toupper(unit[0]))) + 1;
    if (unit.size() > 1 || (power == 0 && !unit.empty()) || !std::isfinite(number)) return bad;
    const double bytes = number * std::pow(1024.0, double(power));
    if (!(bytes >= double(uint64_t(16) << 20)) || bytes > 1e18) return bad;
    settings.memory = uint64_t(bytes);
    return "";
}

// --frame's "WxH" (or W×H): both sides at least 2; "" if it parses, else the message.
std::string parseFrame(const std::string& text, Settings& settings) {
    const std::string bad = "--frame " + text + ": give the points' frame as WIDTHxHEIGHT in input pixels, each at least 2";
    std::string spelled = text;
    if (const size_t times = spelled.find("×"); times != std::string::npos) spelled.replace(times, std::string("×").size(), "x");
    const size_t x = spelled.find('x');
    if (x == std::string::npos || x == 0 || x + 1 == spelled.size()) return bad;
    const std::string sides[2] = {spelled.substr(0, x), spelled.substr(x + 1)};
    uint64_t values[2] = {};
    for (int i = 0; i < 2; ++i) {
        if (sides[i].size() > 9 || sides[i].find_first_not_of("0123456789") != std::string::npos) return bad;
        values[i] = std::stoull(sides[i]);
        if (values[i] < 2) return bad;
    }
    settings.frame_width = uint32_t(values[0]);
    settings.frame_height = uint32_t(values[1]);
    return "";
}

// A factor of -s: a finite number >= 1, the whole text.
bool parseFactor(const std::string& text, double& factor) {
    size_t used = 0;
    try {
        factor = std::stod(text, &used);
    } catch (const std::exception&) {
        return false;
    }
    return used == text.size() && std::isfinite(factor) && factor >= 1.0;
}

// Fills scale, or axis_scales for "FX,FY,FZ"; "" if the text is one of those, else the message.
std::string parseScale(const std::string& text, Settings& settings) {
    if (text.find(',') == std::string::npos) {
        if (!parseFactor(text, settings.scale)) return "--scale must be a number >= 1 (got " + text + ")";
        return "";
    }
    std::array<std::string, 3> parts;
    size_t start = 0;
    for (int a = 0; a < 3; ++a) {
        const size_t comma = a < 2 ? text.find(',', start) : text.size();
        if (comma == std::string::npos) break;
        parts[a] = text.substr(start, comma - start);
        start = comma + 1;
    }
    for (int a = 0; a < 3; ++a)
        if (!parseFactor(parts[a], settings.axis_scales[a]) || text.find(',', start) != std::string::npos)
            return "--scale " + text + ": give one factor, or three (x, y, z: volumes only), each a number >= 1";
    return "";
}

bool perAxisScale(const Settings& settings) { return settings.axis_scales[0] > 0.0; }

// Options given that mean nothing for volumes, as spelled on the command line.
std::vector<std::string> imageOnlyOptions(const CLI::App& app, const Settings& settings) {
    std::vector<std::string> given;
    for (const char* name : {"--quality", "--mesh", "--mesh-height", "--simplify", "--max-error", "--reconstruct",
                             "--assume", "--fallback", "--width", "--height", "--variant", "--no-active-set", "--mask", "--mask-dir", "--memory",
                             "--frame", "--delaunay"})
        if (app.count(name)) given.push_back(name);
    if (settings.depth == "half") given.push_back("--depth half");
    return given;
}

// "" if the parsed values make sense together, else the message.
std::string validateSettings(const CLI::App& app, const Settings& settings) {
    const bool scale_given = app.count("--scale") > 0;
    if (scale_given && (settings.width || settings.height)) return "give either --scale or --width/--height, not both";
    if (app.count("--width") && settings.width == 0) return "--width must be at least 1";
    if (app.count("--height") && settings.height == 0) return "--height must be at least 1";
    if (!settings.variant.empty() && !parseFlipRule(settings.variant))
        return "--variant " + settings.variant + ": unknown flip rule (see --help)";
    if (!settings.variant.empty() && settings.backend != "vulkan") return "--variant needs --backend vulkan";
    if (settings.backend == "cpu" && app.count("--device")) return "--device picks a Vulkan device; --backend cpu uses none";
    if (settings.backend == "cpu" && settings.delaunay == "device")
        return "--delaunay device runs on a Vulkan device; --backend cpu uses none";
    if (settings.backend == "cpu" && !settings.active_set)
        return "--no-active-set applies to the Vulkan backend's parallel flips; --backend cpu flips serially";
    if (settings.tile && settings.tile < kMinTileSide)
        return "--tile must be 0 (automatic) or at least " + std::to_string(kMinTileSide) + " pixels";
    if (!settings.depth.empty() && !parseSampleType(settings.depth))
        return "--depth " + settings.depth + ": use 8, 16, half or float";
    if (!settings.format.empty() && settings.format.find_first_of("./") != std::string::npos)
        return "--format " + settings.format + ": give an extension such as png, jpg, tif or exr";
    if (!settings.cost.empty() && !parseCostFunction(settings.cost))
        return "--cost " + settings.cost + ": use sederberg, variance or face-scf";
    if (settings.list_devices) return "";
    // Volumes named on the command line are checked here, before any work; those found by -i
    // when the batch is planned (app/batch_plan.cpp).
    if (settings.stack && (!settings.singleForm() || settings.inputs.size() != 1))
        return "--stack reads one folder of slices or one multi-page TIFF: `ddtup --stack IN OUT.nrrd`";
    bool any_volume = false;
    for (const std::string& input : settings.inputs)
        if (settings.stack || isVolumePath(input)) {
            any_volume = true;
            if (std::string problem = volumeTaskProblem(input, settings); !problem.empty()) return problem;
        } else if (input != kStandardStream && settings.input_folder.empty() && settings.output_folder.empty() &&
                   perAxisScale(settings)) {
            return "--scale with three factors applies to volumes (" + volumeExtensionNames() + "), not to " + input;
        }
    if (!any_volume && settings.input_folder.empty()) {
        if (!settings.slices.empty()) return "--slices applies to volumes (" + volumeExtensionNames() + ")";
        if (perAxisScale(settings)) return "--scale with three factors applies to volumes (" + volumeExtensionNames() + ")";
    }
    if (settings.singleForm() && !settings.output.empty() &&
        (settings.stack || isVolumePath(settings.inputs.front())) != isVolumePath(settings.output))
        return settings.output + ": a volume's output must be a volume file (" + volumeExtensionNames() +
               ") and an image's an image file";

    const size_t paths = settings.inputs.size();
    if (!settings.input_folder.empty()) {
        if (settings.output_folder.empty()) return "-i needs -o DIR, the folder to write into";
        if (paths) return "give input images either as arguments or with -i DIR, not both";
    } else if (!settings.output_folder.empty()) {
        if (!paths) return "no input images given";
        for (const std::string& input : settings.inputs)
            if (input == kStandardStream) return "standard input (-) works only in the form `ddtup - OUT`";
    } else {
        if (settings.output.empty()) {
            if (!paths) return "no input image given (see --help)";
            return paths == 1 ? "no output given: `ddtup IN OUT`, or -o DIR" : "several inputs need a folder to write into: -o DIR, or an existing folder last";
        }
    }
    if (settings.recursive && settings.input_folder.empty()) return "-r needs -i DIR";
    if (settings.stats && settings.output == kStandardStream) return "--stats prints to standard output; it can't be combined with output -";
    // A terminal holds no image: reading it would wait for ever, writing it would spew bytes.
    if (!settings.inputs.empty() && settings.inputs.front() == kStandardStream && ::isatty(STDIN_FILENO))
        return "standard input is a terminal; pipe an image into `ddtup - OUT`";
    if (settings.output == kStandardStream && ::isatty(STDOUT_FILENO))
        return "standard output is a terminal; redirect it to a file or a pipe";
    if (settings.output == kStandardStream && settings.format.empty() && !std::filesystem::path(settings.inputs.front()).has_extension())
        return "writing to standard output needs -f FORMAT (the input has no extension to follow)";
    if (std::string problem = validateMesh(app, settings); !problem.empty()) return problem;
    if (std::string problem = validateMask(app, settings); !problem.empty()) return problem;
    if (std::string problem = validateAssume(app, settings); !problem.empty()) return problem;
    if (std::string problem = validateFallback(settings); !problem.empty()) return problem;
    if (std::string problem = validateDelaunay(app, settings); !problem.empty()) return problem;
    return validatePoints(app, settings);
}

// CLI11 messages are one line today; keep it that way whatever it says.
std::string oneLine(std::string message) {
    for (char& c : message)
        if (c == '\n') c = ' ';
    return message;
}

// Whether the command line asks for JSON events, read before parsing so that even a
// command line CLI11 rejects gets its error as an event.
bool asksForJson(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--progress=json" || (arg == "--progress" && i + 1 < argc && std::string(argv[i + 1]) == "json"))
            return true;
    }
    return false;
}

}  // namespace

std::optional<Settings> parseCommandLine(int argc, char** argv, int& exit_code) {
    Settings settings;
    CLI::App app{kDescription, "ddtup"};
    app.set_version_flag("--version", std::string("ddtup ") + DDTUP_VERSION);
    app.add_option("paths", settings.inputs, "Images to magnify (" + imageFormatTitles() + "); in the form IN OUT the last is the output");
    app.add_option("-o,--output", settings.output_folder, "Folder to write into (created if missing); each output keeps its input's name")
        ->default_str("none: the form IN OUT");
    app.add_option("-i,--input-dir", settings.input_folder, "Folder whose images to magnify (needs -o)")->default_str("none");
    app.add_flag("-r,--recursive", settings.recursive, "With -i: also the sub-folders, keeping their structure (default: off)");
    app.add_option("-f,--format", settings.format,
                   "Output format by extension: png, jpg, tif, exr, webp, bmp, gif, tga, ppm, pgm, hdr. PNG: 8 or 16 bits (half and "
                   "float become 16), rows filtered or not, whichever compresses better, deflated in parallel (ISA-L; zlib "
                   "where the image is flat)")
        ->default_str("each input's own format");
    app.add_option("--quality", settings.quality, "Quality of lossy formats (jpg, webp), 1 to 100")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    app.add_option("--depth", settings.depth, "Output sample type: 8, 16, half or float")->default_str("the input's");
    app.add_flag("--skip-existing", settings.skip_existing, "Skip images whose output already exists (default: off)");
    app.add_option("--mesh", settings.mesh,
                   "Also write the optimized mesh: FILE.ply (binary), FILE.obj or FILE.svg; in the batch forms ply, "
                   "obj or svg, each mesh beside its output, named like it. Positions in output pixels (input pixel "
                   "centre x at (x + 0.5)·scale), y up in PLY and OBJ, counter-clockwise triangles, a border ring "
                   "out to the image rectangle; straight vertex colours (PLY: as the input's 8, 16 bits or float; "
                   "OBJ: 0 to 1, no alpha; SVG: a linear gradient per triangle, at most 200000 triangles) from the "
                   "input's pixels, i.e. plain DDT's surface whatever --reconstruct says")
        ->default_str("none");
    app.add_option("--simplify", settings.simplify,
                   "Keep this fraction of the mesh's vertices, in (0, 1]: edge collapses in order of least quadric "
                   "error over position and colour (Garland-Heckbert), each merged vertex at the place and colour its quadric calls for "
                   "(to 1/1024 pixel; corners stay, border vertices slide along their side); the output is the linear surface on the simplified mesh, "
                   "and --mesh writes that mesh. The CPU backend simplifies serially; a Vulkan device by a parallel rule "
                   "(rounds of collapses whose neighbourhoods do not touch). An image whose simplification does not fit --memory whole, "
                   "or that --tile cuts, is simplified in tiles whose shared sides keep their pixels. With --mask or a point file, "
                   "the fraction of the known samples, in one piece, their hull kept")
        ->default_str("none");
    app.add_option("--max-error", settings.max_error,
                   "Simplify the mesh (as --simplify does) as far as no collapse errs by more than this: the root-"
                   "mean-square distance, in 8-bit levels (1/255 of the range), from the merged vertices' colour "
                   "planes; with --simplify, whichever limit comes first")
        ->default_str("none");
    app.add_option("--mask", settings.mask,
                   "Reconstruct the input from some of its pixels: those where this image (the input's size) is not "
                   "black are known, the rest are filled in (holes, dead pixels, sparse samples). The known pixels' "
                   "Delaunay triangulation is optimized by the same flips and rendered linearly on each triangle, "
                   "outside their hull with the nearest value. One input; large images in tiles whose crops grow "
                   "around the holes; alpha keeps its "
                   "meaning (transparency) and never marks unknown pixels")
        ->default_str("none: every pixel is known");
    app.add_option("--mask-dir", settings.mask_folder,
                   "--mask for a batch (-i DIR, or several inputs with -o): each input's mask is the image with the "
                   "same name, any extension, in this folder (under the same sub-folder with -r). An input without "
                   "exactly one mask there fails with a message; the others go on")
        ->default_str("none");
    std::string frame_text;
    app.add_option("--frame", frame_text,
                   "For point files (.csv x,y,values or .ply with vertex colours): the frame the points lie in, "
                   "WIDTHxHEIGHT input pixels with pixel centres at 0 … WIDTH − 1 and 0 … HEIGHT − 1; the output "
                   "is this frame magnified. Points are triangulated (Delaunay), optimized by the same flips and "
                   "rendered linearly on each triangle, outside their hull with the nearest value")
        ->default_str("the smallest frame from 0 that holds the points");
    app.add_option("--mesh-height", settings.mesh_height,
                   "With --mesh: z = luma × this, in output pixels (Rec. 709 weights on the stored values), a "
                   "2.5-D relief; 0 keeps the mesh flat")
        ->capture_default_str();
    std::string scale_text;
    app.add_option("-s,--scale", scale_text,
                   "Magnification factor, a real number >= 1 (used when no --width/--height); volumes also take one "
                   "per axis, FX,FY,FZ (e.g. 1,1,2.5 for thick slices)")
        ->default_str("2");
    app.add_option("--width", settings.width,
                   "Output width in pixels; the height keeps the aspect unless --height is given (default: from --scale)");
    app.add_option("--height", settings.height,
                   "Output height in pixels; the width keeps the aspect unless --width is given (default: from --scale)");
    app.add_option("--reconstruct", settings.reconstruct,
                   "The surface on the optimized mesh: consistent (quadratic, corrected so that the output, "
                   "degraded by a pixel footprint, gives the input back) or plain (the paper's DDT: the pixel "
                   "values interpolated linearly)")
        ->check(CLI::IsMember({"consistent", "plain"}))
        ->capture_default_str();
    app.add_option("--assume", settings.assume,
                   "The downscale filter the consistent surface assumes made the input: auto (footprint for a "
                   "JPEG file, mixed for any other), mixed (unknown: the footprint and bicubic mixed), footprint "
                   "(a camera's or an averaging resize's, a Gaussian of 0.4 input pixels), box (area averaging), "
                   "bicubic (Catmull-Rom, an editor's bicubic resize) or lanczos3; the right one gains up to 0.5 dB")
        ->check([](const std::string& name) {
            return name == kAutomaticAssumption || parseAssumedKernel(name)
                       ? ""
                       : "unknown filter " + name + "; use " + kAutomaticAssumption + ", " + assumedKernelNames();
        })
        ->capture_default_str();
    app.add_option("--fallback", settings.fallback,
                   "Where the input has little contrast, blend the surface towards a convolution of the input: "
                   "lanczos3 (the mesh keeps its weight on strong edges; better on photographs' smooth and "
                   "grainy regions) or none (default: lanczos3 with the consistent surface, none with the plain one)")
        ->check(CLI::IsMember({"none", "lanczos3"}));
    app.add_option("--tile", settings.tile,
                   "Tile side in input pixels for images too large for the device (with --mask or a point file, "
                   "each tile's crop grows to hold the gaps between samples near it); for volumes the brick side in "
                   "voxels (optimized one by one, with a margin of 8; automatic: bricks of 128 above 2^22 voxels); "
                   "0 = automatic (the CPU backend on two or more threads also tiles every image beyond 256 pixels, "
                   "one tile per thread at a time, as many tiles a strip as the threads take at once)")
        ->capture_default_str();
    app.add_option("--backend", settings.backend,
                   "auto (Vulkan on a GPU; the CPU backend where the only Vulkan device runs on the CPU, such as "
                   "lavapipe, or where there is none, with a note saying which and why), vulkan (parallel flips "
                   "on a Vulkan device, exit code 3 without one) or cpu")
        ->check(CLI::IsMember({"auto", "vulkan", "cpu"}))
        ->capture_default_str();
    app.add_option("--threads", settings.threads,
                   "CPU threads for everything the run does on the CPU: decoding, optimizing, rendering, encoding")
        ->check(CLI::Range(1u, 1024u))
        ->default_str("the processors ddtup may use (CPU affinity and cgroup quota)");
    std::string memory_text;
    app.add_option("--memory", memory_text,
                   "Host memory the run may hold (512M, 4G …): the images in flight, and on the CPU backend a point "
                   "file's mesh and output (beyond it, tiles), a mask's with --mesh or --simplify, which cannot be "
                   "tiled, or a whole simplification's (beyond it, tiles); automatic tiles stay small within it for speed")
        ->default_str("half the machine's memory");
    app.add_option("--variant", settings.variant,
                   "Vulkan flip rule: basic, exproi, exproi-N-maxgain, maxgain, exproi-maxgain, localmax, exproi-localmax")
        ->default_str(std::string(kDefaultFlipRule) + "; ignored when the CPU backend runs");
    app.add_option("--device", settings.device, "Vulkan device index from --list-devices; asks for the Vulkan backend")
        ->default_str("the first discrete GPU, then integrated, then CPU devices");
    app.add_flag("--list-devices", settings.list_devices, "List the Vulkan devices and exit");
    app.add_option("--delaunay", settings.delaunay,
                   "Masks and point files: where the samples are triangulated (the same triangulation either way): "
                   "auto (the Vulkan device on a GPU, the CPU elsewhere, where it is faster), cpu, or device (asks "
                   "for the Vulkan backend)")
        ->check(CLI::IsMember({"auto", "cpu", "device"}))
        ->capture_default_str();
    app.add_flag("!--no-active-set", settings.active_set,
                 "Vulkan: re-test every edge in every iteration, not only those a flip may have changed (default: off)");
    app.add_option("--cost", settings.cost,
                   "The cost the flips lower. Images: sederberg (Yu et al.'s edge cost), or Toth et al.'s content-"
                   "weighted costs, each triangle's area times a weight: variance (of its three values) or face-scf "
                   "(the mean over its edges of Sederberg's cost). Volumes: the same weights of each tetrahedron's "
                   "volume, variance or face-scf (0 on the box's sides), values normalised by the volume's range")
        ->default_str("sederberg for images, variance for volumes");
    app.add_option("--slices", settings.slices,
                   "Volumes: also write PNG slices through the middle of each output (axial, coronal, sagittal), "
                   "grey levels spanning the output's range, into this folder")
        ->default_str("none");
    app.add_flag("--stack", settings.stack,
                 "Read the input as a volume of 2-D slices: a folder of grey images (in name order) or a multi-page "
                 "TIFF (in page order), unit spacing; one input, and the output a volume file (default: off)");
    std::string progress = "auto";
    app.add_option("--progress", progress,
                   "auto (a progress line on a terminal, nothing otherwise), bar, json (one JSON event per line "
                   "on stderr, errors and notes included) or none")
        ->check(CLI::IsMember({"auto", "bar", "json", "none"}))
        ->capture_default_str();
    app.add_flag("--stats", settings.stats, "Print cost, flips and stage times of each image (default: off)");
    bool quiet = false, verbose = false;
    app.add_flag("-q,--quiet", quiet, "Print nothing but errors (default: off)");
    app.add_flag("-v,--verbose", verbose, "Also print a line per finished image and the device used (default: off)");

    auto usageError = [&](const std::string& message) {
        if (asksForJson(argc, argv))
            std::cerr << JsonLine().field("event", "error").field("message", oneLine(message)).field("exit_code", int(kExitUsage)).text();
        else
            std::cerr << "ddtup: " << oneLine(message) << "\n";
        exit_code = kExitUsage;
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
    if (quiet && verbose) return usageError("give either -q or -v, not both");
    settings.progress = progress == "bar"    ? ProgressMode::Bar
                        : progress == "json" ? ProgressMode::Json
                        : progress == "none" ? ProgressMode::None
                                             : ProgressMode::Auto;
    settings.verbosity = quiet ? Verbosity::Quiet : verbose ? Verbosity::Verbose : Verbosity::Normal;
    if (settings.output_folder.empty() && settings.input_folder.empty() && settings.inputs.size() >= 2) {
        // Like cp: a last argument that is a folder (or ends in "/") is where the outputs go.
        const std::string& last = settings.inputs.back();
        if (last.ends_with('/') || std::filesystem::is_directory(last)) {
            settings.output_folder = last;
            settings.inputs.pop_back();
        } else if (settings.inputs.size() == 2) {
            settings.output = last;
            settings.inputs.pop_back();
        }
    }
    if (app.count("--frame"))
        if (std::string problem = parseFrame(frame_text, settings); !problem.empty()) return usageError(problem);
    if (app.count("--memory"))
        if (std::string problem = parseMemory(memory_text, settings); !problem.empty()) return usageError(problem);
    if (app.count("--scale"))
        if (std::string problem = parseScale(scale_text, settings); !problem.empty()) return usageError(problem);
    settings.image_only_options = imageOnlyOptions(app, settings);
    if (std::string problem = validateSettings(app, settings); !problem.empty()) return usageError(problem);
    if (!app.count("--scale") && !settings.width && !settings.height) settings.scale = 2.0;
    return settings;
}

}  // namespace ddt
