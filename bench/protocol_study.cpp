#include "protocol_study.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>

#include "crops.h"
#include "ddt_magnify.h"
#include "edge_directed.h"
#include "gmsd.h"
#include "image_metadata.h"
#include "protocol.h"
#include "vips_nohalo.h"

namespace bench {

namespace {

const char* const kCropsFolder = "protocols";

void addNote(BenchResults& results, const std::string& note) {
    if (std::find(results.notes.begin(), results.notes.end(), note) == results.notes.end())
        results.notes.push_back(note);
}

// One backend per DDT method for the whole study: creating a Vulkan device is not free.
class DdtBackends {
public:
    ddt::Backend& forMethod(const DdtMethod& method) {
        std::unique_ptr<ddt::Backend>& backend = backends_[method.key];
        if (!backend) backend = makeMethodBackend(method);
        return *backend;
    }

private:
    std::map<std::string, std::unique_ptr<ddt::Backend>> backends_;
};

// Every available column's magnification of `low` to width × height, by Upscaler::key.
std::map<std::string, ddt::Image> magnifyAll(BenchResults& results, DdtBackends& backends, const ddt::Image& low,
                                             uint32_t width, uint32_t height,
                                             const std::string& where) {
    std::map<std::string, ddt::Image> outputs;
    std::set<std::string> ddt_runs;  // method and assumed filter
    auto runKey = [](const Upscaler& u) {
        return u.ddt.key + "/" + (u.assume ? ddt::assumedKernelName(*u.assume) : ddt::kAutomaticAssumption);
    };
    // What the default assumes of `low` (a JPEG protocol's input was read back from a JPEG file).
    const ddt::AssumedKernel automatic = ddt::automaticAssumption(low.metadata ? low.metadata->format_name : "");
    for (const Upscaler& u : results.upscalers) {
        if (!u.unavailable.empty() || (u.kind == UpscalerKind::Ddt && !ddt_runs.insert(runKey(u)).second)) continue;
        try {
            switch (u.kind) {
            case UpscalerKind::OiioFilter:
                outputs[u.key] = resizeWithFilter(low, u.oiio_filter, width, height);
                break;
            case UpscalerKind::Nohalo:
                outputs[u.key] = magnifyWithNohalo(low, width, height);
                break;
            case UpscalerKind::EdgeDirected:
                outputs[u.key] = magnifyWithIcbi(low, width, height);
                break;
            case UpscalerKind::Ddt: {
                // Plain and consistent share one optimisation of the same method (each other
                // assumed filter has its own: a reconstruction may give up the backend's mesh).
                // The fallback's column blends the consistent surface of the same run.
                const Upscaler* plain = nullptr;
                const Upscaler* consistent = nullptr;
                const Upscaler* fallback = nullptr;
                for (const Upscaler& v : results.upscalers)
                    if (v.kind == UpscalerKind::Ddt && runKey(v) == runKey(u) && v.unavailable.empty())
                        (v.fallback ? fallback : v.consistent ? consistent : plain) = &v;
                DdtOutputs ddt = magnifyWithDdt(backends.forMethod(u.ddt), low, width, height, plain != nullptr,
                                                consistent != nullptr, u.assume.value_or(automatic), fallback != nullptr);
                if (plain) outputs[plain->key] = std::move(*ddt.plain);
                if (ddt.consistent) outputs[consistent->key] = std::move(*ddt.consistent);
                if (ddt.fallback) outputs[fallback->key] = std::move(*ddt.fallback);
                if (!ddt.consistent_error.empty())
                    addNote(results, (consistent ? consistent : fallback)->label + " n/a on " + where + ": " +
                                         ddt.consistent_error);
                break;
            }
            }
        } catch (const std::exception& error) {
            addNote(results, u.label + " n/a on " + where + ": " + error.what());
        }
    }
    return outputs;
}

MethodScores score(const ddt::ByteImage& original, const ddt::ByteImage& input, const ddt::Image& output) {
    const ddt::ByteImage bytes = ddt::toBytes(output);
    return {ddt::compareImages(original, bytes), gradientMagnitudeSimilarityDeviation(original, bytes),
            measureOvershoot(input, bytes)};
}

const ddt::Image* find(const std::map<std::string, ddt::Image>& outputs, const std::string& key) {
    auto found = outputs.find(key);
    return found == outputs.end() ? nullptr : &found->second;
}

void printLine(const ProtocolImageResult& r, const std::vector<Upscaler>& upscalers) {
    std::printf("[%s ×%s] %s/%s %ux%u <- %ux%u:", r.protocol.c_str(), r.factor.name().c_str(), r.set.c_str(),
                r.name.c_str(), r.width, r.height, r.low_width, r.low_height);
    for (const Upscaler& u : upscalers)
        if (auto found = r.scores.find(u.key); found != r.scores.end())
            std::printf(" | %s %.2f dB", u.label.c_str(), found->second.quality.psnr);
    std::printf("\n");
    std::fflush(stdout);
}

}  // namespace

bool runProtocolStudy(BenchResults& results, const std::vector<StudyImage>& images, const std::string& crops_dir) {
    const std::string strips_dir = crops_dir + "/" + kCropsFolder;
    std::filesystem::create_directories(strips_dir);
    DdtBackends backends;
    bool labelled = true;
    for (const Protocol& protocol : results.protocols)
        for (Magnification factor : protocol.factors)
            for (const StudyImage& image : images) {
                const ddt::Image original = cropForFactor(image.original, factor);
                const ddt::Image low = protocolLowRes(protocol, original, factor);
                ProtocolImageResult r{protocol.key, factor, image.set, image.name, original.width, original.height,
                                      low.width, low.height, {}};
                const std::string where = protocol.key + " ×" + factor.name() + " " + image.set + "/" + image.name;
                const std::map<std::string, ddt::Image> outputs =
                    magnifyAll(results, backends, low, original.width, original.height, where);
                const ddt::ByteImage original_bytes = ddt::toBytes(original), low_bytes = ddt::toBytes(low);
                for (const auto& [key, output] : outputs) r.scores[key] = score(original_bytes, low_bytes, output);

                // The peers, ddtup's default (the consistent surface with the fallback), its plain
                // surface, the truth.
                const std::vector<CropPanel> panels = {{"Lanczos3", find(outputs, "filter/lanczos3")},
                                                       {"Nohalo", find(outputs, "vips/nohalo")},
                                                       {"ICBI", find(outputs, "icbi")},
                                                       {"ddtup (default)", find(outputs, "cpu+consistent+fallback")},
                                                       {"ddtup plain", find(outputs, "cpu")},
                                                       {"Original", &original}};
                const std::string strip = strips_dir + "/" + protocol.key + "_" + image.set + "_" + image.name + "_x" +
                                          factor.name() + ".png";
                labelled = writeCropStrip(strip, panels, busiestWindow(original, kCropSide), kCropZoom) && labelled;
                printLine(r, results.upscalers);
                results.protocol_images.push_back(std::move(r));
            }
    return labelled;
}

}  // namespace bench
