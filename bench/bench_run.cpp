#include "bench_run.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <set>

#include "crops.h"
#include "image_sets.h"
#include "memory_png.h"
#include "protocol.h"
#include "protocol_study.h"
#include "reference_check.h"
#include "report.h"
#include "scaling.h"

namespace bench {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// --quick: the first image of the first two sets (or the first two of a single set),
// cropped to this square, so that CI runs the whole bench in seconds.
const uint32_t kQuickSide = 128;

void say(const char* format, auto... args) {
    std::printf(format, args...);
    std::fflush(stdout);
}

struct BenchImage {
    std::string set;
    std::string path;
};

std::vector<BenchImage> imagesToRun(const std::vector<ImageSet>& sets, bool quick) {
    std::vector<BenchImage> images;
    for (const ImageSet& set : sets)
        for (const std::string& path : set.paths) images.push_back({set.name, path});
    if (!quick) return images;
    std::vector<BenchImage> chosen;
    for (const ImageSet& set : sets)
        if (chosen.size() < 2) chosen.push_back({set.name, set.paths.front()});
    if (chosen.size() < 2 && sets.front().paths.size() > 1)
        chosen.push_back({sets.front().name, sets.front().paths[1]});
    return chosen;
}

void addNote(BenchResults& results, const std::string& note) {
    if (std::find(results.notes.begin(), results.notes.end(), note) == results.notes.end())
        results.notes.push_back(note);
}

// Every image must still be usable at every factor: DDT needs a low-resolution image of
// 2×2 pixels, SSIM an original of 11×11. Checked before any work starts.
void checkImageSizes(const std::vector<BenchImage>& images, const std::vector<uint32_t>& factors, bool quick) {
    for (const BenchImage& image : images) {
        ImageSize size = imageSize(image.path);
        if (quick) size = {std::min(size.width, kQuickSide), std::min(size.height, kQuickSide)};
        for (uint32_t factor : factors) {
            const uint32_t low_w = size.width / factor, low_h = size.height / factor;
            if (low_w < 2 || low_h < 2 || low_w * factor < 11 || low_h * factor < 11)
                throw ddt::UserError(image.path + ": too small for ×" + std::to_string(factor) +
                                     " (needs a 2×2 low-resolution image and an 11×11 original)");
        }
    }
}

ddt::Image loadForBench(const std::string& path, bool quick, BenchResults& results) {
    std::string note;
    ddt::Image image = loadOriginal(path, note);
    if (!note.empty()) addNote(results, note);
    if (quick && (image.width > kQuickSide || image.height > kQuickSide))
        image = cropCentred(image, std::min(image.width, kQuickSide), std::min(image.height, kQuickSide));
    return image;
}

// The DDT methods to run on every image: Table 1's columns and every device's variants.
std::vector<DdtMethod> runnableMethods(const BenchResults& results) {
    std::vector<DdtMethod> methods;
    std::set<std::string> keys;
    for (const std::vector<DdtMethod>* list : {&results.columns, &results.device_methods})
        for (const DdtMethod& method : *list)
            if (method.unavailable.empty() && keys.insert(method.key).second) methods.push_back(method);
    return methods;
}

// The GPU column the crops show beside CPU DDT: the paper's choice, ExpROI MaxGain.
const DdtMethod& cropGpuMethod(const BenchResults& results) {
    for (const DdtMethod& method : results.columns)
        if (method.variant == "exproi-maxgain") return method;
    return results.columns.back();
}

void printHeader(const BenchResults& results, const BenchOptions& options, size_t image_count) {
    const MachineInfo& m = results.machine;
    say("ddtup-bench%s: %zu images in %zu sets, factors", results.quick ? " --quick" : "", image_count,
        results.set_names.size());
    for (uint32_t factor : results.factors) say(" ×%u", factor);
    say(", writing to %s\n", options.out_dir.c_str());
    say("machine: %s, %u hardware threads; CPU DDT runs serially on one thread; OIIO %s with %d threads (filters, "
        "untimed)\n",
        m.cpu_model.c_str(), m.hardware_threads, m.oiio_version.c_str(), m.oiio_threads);
    if (results.devices.empty()) say("Vulkan devices: none\n");
    for (const BenchDevice& device : results.devices)
        say("Vulkan device %s: %s\n", device.id.c_str(), device.name.c_str());
    say("timing: %u warm-up + %u timed runs per DDT method and image (median); Fig. 13: %u timed runs\n",
        results.warmups, results.repeats, results.scaling_repeats);
    if (results.paper_tables)
        for (const DdtMethod& method : results.columns)
            if (!method.unavailable.empty()) say("  %s: n/a (%s)\n", method.label.c_str(), method.unavailable.c_str());
    for (const Upscaler& u : results.upscalers)
        if (!u.unavailable.empty()) say("  protocol tables, %s: n/a (%s)\n", u.label.c_str(), u.unavailable.c_str());
}

// One original at one factor: every filter and DDT method, its scores and a crop strip.
ImageResult benchImage(const BenchResults& results, const std::vector<DdtMethod>& ddt_methods, const BenchImage& input,
                       const ddt::Image& loaded, uint32_t factor, const std::string& crops_dir, bool& fonts_ok) {
    const ddt::Image original = cropToMultiple(loaded, factor);
    const ddt::Image low = makeLowRes(original, factor);
    const PngInMemory png = encodePng(low);
    const ddt::ByteImage original_bytes = ddt::toBytes(original);

    ImageResult result;
    result.set = input.set;
    result.name = imageName(input.path);
    result.factor = factor;
    result.width = original.width;
    result.height = original.height;
    result.low_width = low.width;
    result.low_height = low.height;

    // Reconstructions the crop strip shows, kept until it is written.
    const DdtMethod& crop_gpu = cropGpuMethod(results);
    std::map<std::string, ddt::Image> kept;
    const std::set<std::string> kept_keys = {"filter/triangle", "filter/lanczos3", "cpu", crop_gpu.key};

    for (const FilterMethod& filter : filterMethods()) {
        const Clock::time_point start = Clock::now();
        ddt::Image magnified = resizeWithFilter(low, filter.oiio_name, original.width, original.height);
        result.filter_seconds[filter.key] = secondsSince(start);
        result.quality[filter.key] = ddt::compareImages(original_bytes, ddt::toBytes(magnified));
        if (kept_keys.count(filter.key)) kept[filter.key] = std::move(magnified);
    }
    for (const DdtMethod& method : ddt_methods) {
        ddt::Image magnified;
        result.ddt[method.key] =
            measureDdt(method, png, {original.width, original.height}, results.warmups, results.repeats, &magnified);
        result.quality[method.key] = ddt::compareImages(original_bytes, ddt::toBytes(magnified));
        if (kept_keys.count(method.key)) kept[method.key] = std::move(magnified);
    }

    auto panel = [&](const std::string& label, const std::string& key) {
        auto found = kept.find(key);
        return CropPanel{label, found == kept.end() ? nullptr : &found->second};
    };
    const std::vector<CropPanel> panels = {{"Original", &original},
                                           panel("Bilinear", "filter/triangle"),
                                           panel("Lanczos", "filter/lanczos3"),
                                           panel("CPU DDT", "cpu"),
                                           panel(crop_gpu.label, crop_gpu.key)};
    const std::string strip_path =
        crops_dir + "/" + result.set + "_" + result.name + "_x" + std::to_string(factor) + ".png";
    fonts_ok = writeCropStrip(strip_path, panels, busiestWindow(original, kCropSide), kCropZoom) && fonts_ok;
    return result;
}

void printImageLine(const ImageResult& r, size_t index, size_t count) {
    say("[×%u %zu/%zu] %s/%s %ux%u <- %ux%u:", r.factor, index, count, r.set.c_str(), r.name.c_str(), r.width, r.height,
        r.low_width, r.low_height);
    say(" bilinear %.2f dB, lanczos3 %.2f dB", r.quality.at("filter/triangle").psnr,
        r.quality.at("filter/lanczos3").psnr);
    for (const auto& [key, m] : r.ddt)
        say(" | %s %.2f dB, SSIM %.4f, %llu flips, %.3f s", key.c_str(), r.quality.at(key).psnr, r.quality.at(key).ssim,
            static_cast<unsigned long long>(m.runs.front().stats.flips), m.medianSum());
    say("\n");
}

void runScaling(BenchResults& results, const std::vector<BenchImage>& images, const BenchOptions& options) {
    const std::string scaling_path = options.scaling_image.empty() ? images.front().path : options.scaling_image;
    results.scaling_image = scaling_path;
    const ddt::Image source = loadForBench(scaling_path, false, results);
    for (uint32_t side : scalingSides(options.scaling_max_side)) {
        const Clock::time_point start = Clock::now();
        for (ScalingResult& r : measureScaling(results.scaling_methods, "resized", imageName(scaling_path),
                                               resizedSquare(source, side), results.warmups, results.scaling_repeats))
            results.scaling.push_back(std::move(r));
        say("[Fig. 13] %s resized to %u×%u: %.1f s\n", imageName(scaling_path).c_str(), side, side,
            secondsSince(start));
    }
    for (const BenchImage& image : images) {
        const ddt::Image original = roundedTo8Bit(loadForBench(image.path, results.quick, results));
        for (ScalingResult& r : measureScaling(results.scaling_methods, "set", image.set + "/" + imageName(image.path),
                                               original, results.warmups, results.scaling_repeats)) {
            say("[Fig. 13] %s %ux%u %s: %.3f s\n", r.image.c_str(), r.width, r.height, r.method_key.c_str(),
                r.measurement.medianSum());
            results.scaling.push_back(std::move(r));
        }
    }
}

}  // namespace

void runBench(const BenchOptions& options) {
    const Clock::time_point start = Clock::now();
    BenchResults results;
    results.machine = describeMachine();
    results.quick = options.quick;
    results.warmups = options.warmups;
    results.repeats = options.repeats;
    results.scaling_repeats = options.scaling_repeats;
    results.factors = options.factors;

    const std::vector<ImageSet> sets = findImageSets(options.data_dirs);
    for (const ImageSet& set : sets) results.set_names.push_back(set.name);
    const std::vector<BenchImage> images = imagesToRun(sets, options.quick);
    std::vector<uint32_t> checked_factors = results.factors;
    if (options.tables != "paper") checked_factors.push_back(8);  // the protocol tables' largest
    checkImageSizes(images, checked_factors, options.quick);

    results.devices = benchDevices(options.device);
    results.columns = ddtMethods(results.devices.empty() ? nullptr : &results.devices.front());
    for (const BenchDevice& device : results.devices)
        for (const DdtMethod& method : ddtMethods(&device))
            if (method.backend != "cpu") results.device_methods.push_back(method);
    results.scaling_methods = scalingMethods(results.devices.empty() ? nullptr : &results.devices.front());
    const std::vector<DdtMethod> ddt_methods = runnableMethods(results);

    const std::string crops_dir = options.out_dir + "/crops";
    std::error_code ec;
    fs::create_directories(crops_dir, ec);
    if (ec) throw ddt::UserError(crops_dir + ": cannot create the folder (" + ec.message() + ")");
    results.paper_tables = options.tables != "protocols";
    if (options.tables != "paper") {
        results.protocols = benchProtocols(options.protocol_filter, options.quick);
        UpscalerSetup setup = protocolUpscalers(results.devices.empty() ? nullptr : &results.devices.front());
        results.upscalers = selectedColumns(std::move(setup.upscalers), options.columns);
        for (const std::string& note : setup.notes) addNote(results, note);
    }
    printHeader(results, options, images.size());

    bool fonts_ok = true;
    if (results.paper_tables) {
        for (uint32_t factor : results.factors)
            for (size_t i = 0; i < images.size(); ++i) {
                const ddt::Image loaded = loadForBench(images[i].path, results.quick, results);
                results.images.push_back(
                    benchImage(results, ddt_methods, images[i], loaded, factor, crops_dir, fonts_ok));
                printImageLine(results.images.back(), i + 1, images.size());
            }
    }
    if (!results.protocols.empty()) {
        const Clock::time_point protocols_start = Clock::now();
        std::vector<StudyImage> originals;
        for (const BenchImage& image : images)
            originals.push_back({image.set, imageName(image.path), loadForBench(image.path, results.quick, results)});
        fonts_ok = runProtocolStudy(results, originals, crops_dir) && fonts_ok;
        say("protocol tables: %.0f s\n", secondsSince(protocols_start));
    }
    if (!fonts_ok)
        addNote(results,
                "no DejaVuSans font for OIIO's render_text: the crop strips are unlabelled; their panels "
                "are, left to right, original, bilinear, Lanczos, CPU DDT, GPU ExpROI MaxGain (crops/protocols: "
                "original, Lanczos3, CPU DDT, CPU DDT consistent)");
    if (results.paper_tables) runScaling(results, images, options);

    results.wall_seconds = secondsSince(start);
    writeReport(results, options.out_dir);
    say("done in %.0f s; report: %s/report.md\n", results.wall_seconds, options.out_dir.c_str());
    for (const std::string& mismatch : referenceMismatches(results))
        say("outside the PLATFORM.md reference: %s\n", mismatch.c_str());
}

}  // namespace bench
