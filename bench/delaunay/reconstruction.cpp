#include "reconstruction.h"

#include <cctype>
#include <chrono>
#include <cmath>
#include <limits>

#include "cgal_peer.h"
#include "child_run.h"
#include "cost.h"
#include "delaunay.h"
#include "gmic_peer.h"
#include "image_file.h"
#include "lawson.h"
#include "metrics.h"
#include "sampled_render.h"

namespace bench {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// `image` with the unknown pixels zeroed: what every method is given.
ddt::Image knownOnly(const ddt::Image& image, const std::vector<uint32_t>& known) {
    ddt::Image result = image;
    std::fill(result.pixels.begin(), result.pixels.end(), 0.0f);
    for (uint32_t v : known)
        std::copy_n(image.pixels.data() + size_t(v) * image.channels, image.channels,
                    result.pixels.data() + size_t(v) * image.channels);
    return result;
}

// PSNR as core/metrics.h defines it (8-bit colour values), over the colour channels of `pixels` only.
double psnrOver(const ddt::ByteImage& original, const ddt::ByteImage& other, const std::vector<uint32_t>& pixels) {
    const uint32_t c = original.channels;
    double sum = 0.0;
    for (uint32_t v : pixels)
        for (uint32_t k = 0; k < c; ++k) {
            const double d = double(original.values[size_t(v) * c + k]) - double(other.values[size_t(v) * c + k]);
            sum += d * d;
        }
    const double mse = sum / (double(pixels.size()) * c);
    return mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(255.0 * 255.0 / mse);
}

struct Scorer {
    ddt::ByteImage original;
    std::vector<uint32_t> unknown;
    std::string pictures;  // ReconstructionOptions::pictures

    void score(Reconstruction& r, const ddt::Image& result) const {
        if (!pictures.empty()) ddt::writeImage(pictures + slugOf(r.method) + ".png", result);
        const ddt::ByteImage bytes = ddt::toBytes(result);
        r.psnr_all = ddt::peakSignalToNoiseRatio(original, bytes);
        r.psnr_unknown = psnrOver(original, bytes, unknown);
    }
};

// Linear on the Delaunay mesh (cost: none) or DDT (the serial reference's flips under `cost`).
Reconstruction meshMethod(const std::string& name, const ddt::Image& values, const std::vector<uint32_t>& known,
                          const ddt::CostFunction* cost, ddt::Backend* backend, const Scorer& scorer) {
    Reconstruction r;
    r.method = name;
    const auto start = Clock::now();
    const double cpu_start = processCpuSeconds();
    ddt::Mesh mesh = ddt::delaunayOfPixels(values.width, values.height, known);
    if (backend) {
        backend->prepareFrom(values, std::move(mesh));
        r.flips = backend->optimize().flips;
        mesh = backend->mesh();
    } else if (cost) {
        ddt::LawsonOptions options;
        options.cost = *cost;
        r.flips = ddt::optimizeSerial(mesh, ddt::costFieldOf(values), options).flips;
    }
    const ddt::Image result = ddt::renderSampledMesh(mesh, values, {values.width, values.height});
    r.cpu_seconds = processCpuSeconds() - cpu_start;
    r.seconds = secondsSince(start);
    scorer.score(r, result);
    return r;
}

}  // namespace

std::string slugOf(const std::string& method) {
    std::string slug;
    for (char c : method) {
        if (std::isalnum(static_cast<unsigned char>(c))) slug += char(std::tolower(static_cast<unsigned char>(c)));
        else if (!slug.empty() && slug.back() != '-') slug += '-';
    }
    while (!slug.empty() && slug.back() == '-') slug.pop_back();
    return slug;
}

std::vector<Reconstruction> reconstructAll(const ddt::Image& original, const std::vector<uint32_t>& known, bool blobs,
                                           const ReconstructionOptions& options) {
    Scorer scorer;
    scorer.original = ddt::toBytes(original);
    scorer.pictures = options.pictures;
    for (uint32_t v = 0, i = 0; v < original.width * original.height; ++v) {
        if (i < known.size() && known[i] == v) ++i;
        else scorer.unknown.push_back(v);
    }
    const ddt::Image values = knownOnly(original, known);
    if (!options.pictures.empty()) ddt::writeImage(options.pictures + "known.png", values);
    std::vector<Reconstruction> rows;

    rows.push_back(meshMethod("linear (Delaunay)", values, known, nullptr, nullptr, scorer));
    const ddt::CostFunction sederberg = ddt::CostFunction::sederberg, variance = ddt::CostFunction::variance;
    rows.push_back(meshMethod("DDT, sederberg", values, known, &sederberg, nullptr, scorer));
    if (options.variance) rows.push_back(meshMethod("DDT, variance", values, known, &variance, nullptr, scorer));
    if (options.vulkan) rows.push_back(meshMethod("DDT, sederberg, Vulkan", values, known, nullptr, options.vulkan, scorer));

    Reconstruction nn;
    nn.method = "natural neighbour (CGAL)";
    const auto start = Clock::now();
    const double cpu_start = processCpuSeconds();
    const ddt::Image nn_image = cgalNaturalNeighbours(values, known);
    nn.cpu_seconds = processCpuSeconds() - cpu_start;
    nn.seconds = secondsSince(start);
    scorer.score(nn, nn_image);
    rows.push_back(nn);

    if (blobs && options.gmic) {
        struct Peer {
            const char *name, *command, *arguments;
        };
        for (const Peer& peer : {Peer{"G'MIC inpaint_pde", "inpaint_pde", ""},
                                 Peer{"G'MIC inpaint, patch 7", "inpaint", ",7"}}) {
            Reconstruction g;
            g.method = peer.name;
            GmicResult result = gmicInpaint(values, known, peer.command, peer.arguments);
            g.failure = result.failure;
            g.seconds = result.seconds;
            g.cpu_seconds = result.cpu_seconds;
            if (g.failure.empty()) scorer.score(g, result.image);
            rows.push_back(g);
        }
    }
    return rows;
}

}  // namespace bench
