#include "ddt_magnify.h"

#include "convolution_fallback.h"

namespace bench {

namespace {

ddt::Image render(ddt::Backend& backend, const ddt::Image& low, uint32_t width, uint32_t height) {
    ddt::Image out;
    out.width = width;
    out.height = height;
    out.channels = low.channels;
    out.sample_type = low.sample_type;
    out.pixels.resize(size_t(width) * height * low.channels);
    backend.renderRows({width, height}, 0, height, out.pixels.data());
    return out;
}

// A small picture with an edge and a gradient, so the optimisation has flips to do.
ddt::Image probeImage() {
    const uint32_t side = 16;
    ddt::Image image;
    image.width = image.height = side;
    image.channels = 1;
    for (uint32_t y = 0; y < side; ++y)
        for (uint32_t x = 0; x < side; ++x) image.pixels.push_back(x + y < side ? float(x) / side : 1.0f);
    return image;
}

}  // namespace

DdtOutputs magnifyWithDdt(ddt::Backend& backend, const ddt::Image& low, uint32_t width, uint32_t height, bool plain,
                          bool consistent, ddt::AssumedKernel assume, bool fallback) {
    DdtOutputs outputs;
    backend.prepare(low);
    backend.optimize();
    if (plain) outputs.plain = render(backend, low, width, height);
    if (!consistent && !fallback) return outputs;
    try {
        backend.reconstruct(ddt::degradationFor(double(width) / low.width, double(height) / low.height, assume));
        if (consistent) outputs.consistent = render(backend, low, width, height);
        if (fallback) {
            backend.addFallback(ddt::grainShareFor(assume));
            outputs.fallback = render(backend, low, width, height);
        }
    } catch (const ddt::UserError& error) {
        outputs.consistent_error = error.what();
    }
    return outputs;
}

std::string consistentUnavailableReason(const DdtMethod& method) {
    if (!method.unavailable.empty()) return method.unavailable;
    try {
        const ddt::Image image = probeImage();
        const DdtOutputs outputs = magnifyWithDdt(*makeMethodBackend(method), image, 32, 32, false, true);
        return outputs.consistent_error;
    } catch (const std::exception& error) {
        return error.what();
    }
}

}  // namespace bench
