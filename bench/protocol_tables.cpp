#include "protocol_tables.h"

#include <functional>

namespace bench {

namespace {

const char* const kAllImages = "all images";

std::vector<std::string> setsAndAll(const BenchResults& results) {
    std::vector<std::string> sets = results.set_names;
    sets.push_back(kAllImages);
    return sets;
}

std::vector<const ProtocolImageResult*> imagesOf(const BenchResults& results, const std::string& protocol,
                                                 Magnification factor, const std::string& set) {
    std::vector<const ProtocolImageResult*> images;
    for (const ProtocolImageResult& image : results.protocol_images)
        if (image.protocol == protocol && image.factor == factor && (set == kAllImages || image.set == set))
            images.push_back(&image);
    return images;
}

using ScoreValue = std::function<double(const MethodScores&)>;

// The mean over `images`, or nothing if any image lacks the method.
std::optional<double> meanOf(const std::vector<const ProtocolImageResult*>& images, const std::string& key,
                             const ScoreValue& value) {
    if (images.empty()) return std::nullopt;
    double total = 0.0;
    for (const ProtocolImageResult* image : images) {
        auto found = image->scores.find(key);
        if (found == image->scores.end()) return std::nullopt;
        total += value(found->second);
    }
    return total / double(images.size());
}

}  // namespace

std::optional<double> protocolMean(const BenchResults& results, const std::string& protocol, Magnification factor,
                                   const std::string& set, const std::string& key, const ScoreValue& value) {
    return meanOf(imagesOf(results, protocol, factor, set), key, value);
}

namespace {

std::optional<double> difference(std::optional<double> a, std::optional<double> b) {
    if (!a || !b) return std::nullopt;
    return *a - *b;
}

double psnr(const MethodScores& s) { return s.quality.psnr; }

}  // namespace

Table protocolQualityTable(const BenchResults& results) {
    Table table;
    table.corner = "Method";
    table.key_names = {"protocol", "factor", "set"};
    table.label_name = "method";
    const std::pair<const char*, ScoreValue> metrics[] = {
        {"PSNR (dB)", psnr},
        {"SSIM", [](const MethodScores& s) { return s.quality.ssim; }},
        {"GMSD", [](const MethodScores& s) { return s.gmsd; }},
        {"Overshoot (levels)", [](const MethodScores& s) { return s.overshoot.nearest_4x4.mean_levels; }},
        {"Overshoot > 4 (%)", [](const MethodScores& s) { return 100.0 * s.overshoot.nearest_4x4.share_over_4; }},
    };
    for (const auto& [label, value] : metrics) table.columns.push_back(label);
    for (const Protocol& protocol : results.protocols)
        for (Magnification factor : protocol.factors)
            for (const std::string& set : setsAndAll(results)) {
                const auto images = imagesOf(results, protocol.key, factor, set);
                const std::string section = "Protocol " + protocol.key + ", ×" + factor.name() + ", " + set;
                for (const Upscaler& u : results.upscalers) {
                    TableRow row{{protocol.key, factor.name(), set}, section, u.label, {}, 4};
                    for (const auto& [label, value] : metrics) row.values.push_back(meanOf(images, u.key, value));
                    table.rows.push_back(row);
                }
            }
    return table;
}

Table consistentGainTable(const BenchResults& results) {
    Table table;
    table.corner = "Mean PSNR difference (dB)";
    table.key_names = {"protocol", "factor"};
    table.label_name = "set";
    table.columns = {"CPU consistent − Lanczos3", "CPU consistent − CPU DDT", "GPU consistent − Lanczos3",
                     "Nohalo − Lanczos3"};
    std::string gpu_consistent;
    for (const Upscaler& u : results.upscalers)
        if (u.consistent && u.ddt.backend == "vulkan") gpu_consistent = u.key;
    for (const Protocol& protocol : results.protocols)
        for (Magnification factor : protocol.factors)
            for (const std::string& set : setsAndAll(results)) {
                const auto images = imagesOf(results, protocol.key, factor, set);
                auto mean = [&](const std::string& key) { return meanOf(images, key, psnr); };
                TableRow row{{protocol.key, factor.name()}, "Protocol " + protocol.key + ", ×" + factor.name(), set,
                             {}, 2};
                row.values = {difference(mean("cpu+consistent"), mean("filter/lanczos3")),
                              difference(mean("cpu+consistent"), mean("cpu")),
                              difference(mean(gpu_consistent), mean("filter/lanczos3")),
                              difference(mean("vips/nohalo"), mean("filter/lanczos3"))};
                table.rows.push_back(row);
            }
    return table;
}

}  // namespace bench
