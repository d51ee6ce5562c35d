#include "reference_check.h"

#include <cmath>
#include <cstdio>
#include <optional>

namespace bench {

namespace {

struct Reference {
    uint32_t factor;
    const char* set;  // "real", "artificial", or "" for all images
    const char* method_key;
    bool ssim;  // false: PSNR (dB)
    double value;
};

// PLATFORM.md, "Reference numbers for the evaluation protocol" (given to 2 and 4 decimals).
const Reference kReferences[] = {
    {4, "", "cpu", false, 23.09},
    {4, "", "cpu", true, 0.7275},
    {4, "", "filter/triangle", false, 22.68},
    {4, "", "filter/triangle", true, 0.7131},
    {4, "", "filter/bspline", false, 22.01},
    {4, "", "filter/bspline", true, 0.6871},
    {4, "", "filter/lanczos3", false, 23.54},
    {4, "", "filter/lanczos3", true, 0.7418},
    {4, "", "filter/catmull-rom", false, 23.27},
    {4, "", "filter/catmull-rom", true, 0.7337},
    {8, "", "cpu", false, 20.11},
    {8, "", "cpu", true, 0.6167},
    {8, "", "filter/triangle", false, 19.83},
    {8, "", "filter/bspline", false, 19.28},
    {8, "", "filter/lanczos3", false, 20.51},
    {8, "", "filter/catmull-rom", false, 20.29},
    {4, "real", "cpu", false, 23.79},
    {4, "real", "cpu", true, 0.6503},
    {4, "real", "filter/triangle", false, 23.55},
    {4, "real", "filter/triangle", true, 0.6396},
    {4, "real", "filter/bspline", false, 22.99},
    {4, "real", "filter/bspline", true, 0.6128},
    {4, "real", "filter/lanczos3", false, 24.22},
    {4, "real", "filter/lanczos3", true, 0.6684},
    {4, "real", "filter/catmull-rom", false, 24.02},
    {4, "real", "filter/catmull-rom", true, 0.6596},
    {4, "artificial", "cpu", false, 22.03},
    {4, "artificial", "cpu", true, 0.8434},
    {4, "artificial", "filter/triangle", false, 21.38},
    {4, "artificial", "filter/triangle", true, 0.8232},
    {4, "artificial", "filter/bspline", false, 20.54},
    {4, "artificial", "filter/bspline", true, 0.7984},
    {4, "artificial", "filter/lanczos3", false, 22.50},
    {4, "artificial", "filter/lanczos3", true, 0.8518},
    {4, "artificial", "filter/catmull-rom", false, 22.16},
    {4, "artificial", "filter/catmull-rom", true, 0.8448},
    {8, "real", "cpu", false, 21.34},
    {8, "real", "cpu", true, 0.5415},
    {8, "real", "filter/lanczos3", false, 21.72},
    {8, "real", "filter/lanczos3", true, 0.5514},
    {8, "artificial", "cpu", false, 18.25},
    {8, "artificial", "cpu", true, 0.7296},
    {8, "artificial", "filter/lanczos3", false, 18.69},
    {8, "artificial", "filter/lanczos3", true, 0.7354},
};

// The acceptance tolerances.
const double kPsnrTolerance = 0.05, kSsimTolerance = 0.002;

size_t countImages(const BenchResults& results, const std::string& set, uint32_t factor) {
    size_t count = 0;
    for (const ImageResult& image : results.images) count += image.set == set && image.factor == factor;
    return count;
}

// The reference numbers describe the bundled sets, uncropped: 12 real and 8 artificial.
bool appliesTo(const BenchResults& results, uint32_t factor) {
    return !results.quick && countImages(results, "real", factor) == 12 &&
           countImages(results, "artificial", factor) == 8;
}

std::optional<double> measured(const BenchResults& results, const Reference& ref) {
    double total = 0.0;
    size_t count = 0;
    for (const ImageResult& image : results.images) {
        if (image.factor != ref.factor || (*ref.set && image.set != ref.set)) continue;
        if (*ref.set == '\0' && image.set != "real" && image.set != "artificial") continue;
        auto found = image.quality.find(ref.method_key);
        if (found == image.quality.end()) return std::nullopt;
        total += ref.ssim ? found->second.ssim : found->second.psnr;
        ++count;
    }
    if (count == 0) return std::nullopt;
    return total / double(count);
}

struct Comparison {
    const Reference* ref;
    double value;
    double tolerance;
    bool within() const { return std::fabs(value - ref->value) <= tolerance; }
};

std::vector<Comparison> compare(const BenchResults& results) {
    std::vector<Comparison> comparisons;
    for (const Reference& ref : kReferences) {
        if (!appliesTo(results, ref.factor)) continue;
        if (std::optional<double> value = measured(results, ref))
            comparisons.push_back({&ref, *value, ref.ssim ? kSsimTolerance : kPsnrTolerance});
    }
    return comparisons;
}

std::string describe(const Reference& ref) {
    return "×" + std::to_string(ref.factor) + " " + (*ref.set ? ref.set : "all images") + " " + ref.method_key + " " +
           (ref.ssim ? "SSIM" : "PSNR");
}

}  // namespace

std::string referenceCheckMarkdown(const BenchResults& results) {
    const std::vector<Comparison> comparisons = compare(results);
    if (comparisons.empty()) return "";
    std::string text =
        "| factor | set | method | metric | measured | reference | difference | tolerance | within |\n"
        "|---|---|---|---|---:|---:|---:|---:|---|\n";
    for (const Comparison& c : comparisons) {
        char line[256];
        const int decimals = c.ref->ssim ? 4 : 3;
        std::snprintf(line, sizeof line, "| ×%u | %s | %s | %s | %.*f | %.*f | %+.*f | ±%g | %s |\n", c.ref->factor,
                      *c.ref->set ? c.ref->set : "all images", c.ref->method_key, c.ref->ssim ? "SSIM" : "PSNR (dB)",
                      decimals, c.value, decimals, c.ref->value, decimals, c.value - c.ref->value, c.tolerance,
                      c.within() ? "yes" : "**no**");
        text += line;
    }
    return text;
}

std::vector<std::string> referenceMismatches(const BenchResults& results) {
    std::vector<std::string> lines;
    for (const Comparison& c : compare(results))
        if (!c.within()) {
            char line[256];
            std::snprintf(line, sizeof line, "%s: measured %.4f, reference %.4f (tolerance ±%g)",
                          describe(*c.ref).c_str(), c.value, c.ref->value, c.tolerance);
            lines.push_back(line);
        }
    return lines;
}

}  // namespace bench
