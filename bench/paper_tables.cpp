#include "paper_tables.h"

#include <functional>

#include "protocol_tables.h"

namespace bench {

namespace {

const char* const kAllImages = "all images";

std::string factorName(uint32_t factor) { return "×" + std::to_string(factor); }

std::vector<const ImageResult*> imagesOf(const BenchResults& results, uint32_t factor, const std::string& set) {
    std::vector<const ImageResult*> images;
    for (const ImageResult& image : results.images)
        if (image.factor == factor && (set == kAllImages || image.set == set)) images.push_back(&image);
    return images;
}

// The mean of `value` over `images`, or nothing if any image lacks it.
std::optional<double> meanOf(const std::vector<const ImageResult*>& images,
                             const std::function<std::optional<double>(const ImageResult&)>& value) {
    if (images.empty()) return std::nullopt;
    double total = 0.0;
    for (const ImageResult* image : images) {
        const std::optional<double> v = value(*image);
        if (!v) return std::nullopt;
        total += *v;
    }
    return total / double(images.size());
}

using DdtValue = std::function<double(const DdtMeasurement&)>;

std::optional<double> meanDdt(const std::vector<const ImageResult*>& images, const std::string& key,
                              const DdtValue& value) {
    return meanOf(images, [&](const ImageResult& image) -> std::optional<double> {
        auto found = image.ddt.find(key);
        if (found == image.ddt.end()) return std::nullopt;
        return value(found->second);
    });
}

using QualityValue = std::function<double(const ddt::QualityScores&)>;

std::optional<double> meanQuality(const std::vector<const ImageResult*>& images, const std::string& key,
                                  const QualityValue& value) {
    return meanOf(images, [&](const ImageResult& image) -> std::optional<double> {
        auto found = image.quality.find(key);
        if (found == image.quality.end()) return std::nullopt;
        return value(found->second);
    });
}

// Every run of a method gives the same mesh; the statistics are those of the first.
const ddt::OptimizeStats& statsOf(const DdtMeasurement& m) { return m.runs.front().stats; }

}  // namespace

Table costAndTimeTable(const BenchResults& results) {
    Table table;
    table.corner = "Average of";
    table.key_names = {"factor", "set"};
    table.label_name = "quantity";
    for (const DdtMethod& method : results.columns) table.columns.push_back(method.label);
    const std::pair<const char*, DdtValue> averaged[] = {
        {"Num. of flips", [](const DdtMeasurement& m) { return double(statsOf(m).flips); }},
        // Beyond the paper: what bounds a parallel run (sweeps for the CPU).
        {"Iterations", [](const DdtMeasurement& m) { return double(statsOf(m).iterations); }},
        {"Accept/reject rounds", [](const DdtMeasurement& m) { return double(statsOf(m).rounds); }},
        {"Dispatches", [](const DdtMeasurement& m) { return double(statsOf(m).dispatches); }},
        {"Time-init. (s)", [](const DdtMeasurement& m) { return m.median.init_s; }},
        {"Time-comp. (s)", [](const DdtMeasurement& m) { return m.median.comp_s; }},
        {"Time-final. (s)", [](const DdtMeasurement& m) { return m.median.final_s; }},
        {"Time-sum (s)", [](const DdtMeasurement& m) { return m.medianSum(); }},
    };
    std::vector<std::string> sets = results.set_names;
    if (sets.size() > 1) sets.push_back(kAllImages);
    for (uint32_t factor : results.factors)
        for (const std::string& set : sets) {
            const std::vector<const ImageResult*> images = imagesOf(results, factor, set);
            const std::vector<std::string> keys = {std::to_string(factor), set};
            const std::string section = "Speed and cost measurement — " + set + (set == kAllImages ? "" : " test set") +
                                        ", " + factorName(factor);
            TableRow cost_init{keys, section, "Cost-init.", {}, 3};
            TableRow cost_final{keys, section, "Cost-final", {}, 3};
            TableRow improvement{keys, section, "Improvement (%)", {}, 3};
            for (const DdtMethod& method : results.columns) {
                auto init = meanDdt(images, method.key, [](const DdtMeasurement& m) { return statsOf(m).cost_init; });
                auto final = meanDdt(images, method.key, [](const DdtMeasurement& m) { return statsOf(m).cost_final; });
                cost_init.values.push_back(init);
                cost_final.values.push_back(final);
                improvement.values.push_back(init && final && *final > 0.0 ? std::optional(100.0 * *init / *final)
                                                                           : std::nullopt);
            }
            // The mean over images of each image's cost-final relative to CPU DDT's: the paper's
            // observation (GPU variants end above serial Lawson) as a measured number. A column
            // with another cost than Sederberg's is compared with CPU DDT of its own cost.
            TableRow ratio{keys, section, "Cost-final / CPU DDT", {}, 4};
            for (const DdtMethod& method : results.columns)
                ratio.values.push_back(meanOf(images, [&](const ImageResult& image) -> std::optional<double> {
                    auto variant = image.ddt.find(method.key), serial = image.ddt.find(cpuKeyFor(method.cost));
                    if (variant == image.ddt.end() || serial == image.ddt.end()) return std::nullopt;
                    return statsOf(variant->second).cost_final / statsOf(serial->second).cost_final;
                }));
            table.rows.insert(table.rows.end(), {cost_init, cost_final, improvement, ratio});
            for (const auto& [label, value] : averaged) {
                // Times get four decimals: a serial run on these small inputs takes milliseconds.
                const bool count = std::string(label).rfind("Time", 0) != 0;
                TableRow row{keys, section, label, {}, count ? 0 : 4};
                for (const DdtMethod& method : results.columns)
                    row.values.push_back(meanDdt(images, method.key, value));
                table.rows.push_back(row);
            }
        }
    return table;
}

Table deviceTimeTable(const BenchResults& results) {
    Table table;
    table.corner = "Average time-sum (s) on";
    table.key_names = {"factor", "set"};
    table.label_name = "device";
    // One column per GPU variant and cost, in Table 1's order.
    std::vector<const DdtMethod*> variants;
    for (const DdtMethod& method : results.columns)
        if (method.backend == "vulkan") {
            table.columns.push_back(method.label);
            variants.push_back(&method);
        }
    for (uint32_t factor : results.factors)
        for (const std::string& set : results.set_names) {
            const std::vector<const ImageResult*> images = imagesOf(results, factor, set);
            const std::vector<std::string> keys = {std::to_string(factor), set};
            const std::string section = "Time-sum — " + set + " test set, " + factorName(factor);
            if (results.devices.empty()) {
                TableRow none{keys, section, "(no Vulkan device)", {}, 3};
                none.values.assign(variants.size(), std::nullopt);
                table.rows.push_back(none);
            }
            for (const BenchDevice& device : results.devices) {
                TableRow row{keys, section, device.name + " [" + device.id + "]", {}, 4};
                for (const DdtMethod* variant : variants) {
                    std::optional<double> value;
                    for (const DdtMethod& method : results.device_methods)
                        if (method.device == device.id && method.variant == variant->variant &&
                            method.cost == variant->cost)
                            value = meanDdt(images, method.key, [](const DdtMeasurement& m) { return m.medianSum(); });
                    row.values.push_back(value);
                }
                table.rows.push_back(row);
            }
        }
    return table;
}

Table qualityTable(const BenchResults& results) {
    Table table;
    table.corner = "Average of";
    table.key_names = {"factor", "set"};
    table.label_name = "metric";
    std::vector<std::string> keys_in_order;
    for (const FilterMethod& filter : filterMethods()) {
        table.columns.push_back(filter.label);
        keys_in_order.push_back(filter.key);
    }
    for (const DdtMethod& method : results.columns) {
        table.columns.push_back(method.label);
        keys_in_order.push_back(method.key);
    }
    const std::pair<const char*, QualityValue> metrics[] = {
        {"PSNR (dB)", [](const ddt::QualityScores& q) { return q.psnr; }},
        {"Correlation (%)", [](const ddt::QualityScores& q) { return 100.0 * q.correlation; }},
        {"Cross cor. (%)", [](const ddt::QualityScores& q) { return 100.0 * q.cross_correlation; }},
        {"MSE", [](const ddt::QualityScores& q) { return q.mse; }},
        {"SNR (dB)", [](const ddt::QualityScores& q) { return q.snr; }},
        {"UIQI", [](const ddt::QualityScores& q) { return q.uiqi; }},
        {"SSIM", [](const ddt::QualityScores& q) { return q.ssim; }},
    };
    // The consistent surface's column comes from the protocol tables' protocol A, which is
    // this table's protocol on the same originals (absent when they did not run): the default
    // surface's, not one assuming another filter or blended by the fallback.
    const Upscaler* consistent = nullptr;
    for (const Upscaler& u : results.upscalers)
        if (u.kind == UpscalerKind::Ddt && u.consistent && u.ddt.backend == "cpu" &&
            !u.assume && !u.fallback && !consistent)
            consistent = &u;
    if (consistent) table.columns.push_back(consistent->label + " (protocol tables)");
    std::vector<std::string> sets = results.set_names;
    sets.push_back(kAllImages);
    for (uint32_t factor : results.factors)
        for (const std::string& set : sets) {
            const std::vector<const ImageResult*> images = imagesOf(results, factor, set);
            const std::string what = set == kAllImages ? std::string(kAllImages) : set + " test set";
            const std::string section = "Quality measurement — " + what + ", " + factorName(factor);
            for (const auto& [label, value] : metrics) {
                TableRow row{{std::to_string(factor), set}, section, label, {}, 4};
                for (const std::string& key : keys_in_order) row.values.push_back(meanQuality(images, key, value));
                if (consistent)
                    row.values.push_back(protocolMean(results, "A", Magnification{factor, 1}, set, consistent->key,
                                                      [&](const MethodScores& s) { return value(s.quality); }));
                table.rows.push_back(row);
            }
        }
    return table;
}

}  // namespace bench
