#include "protocol_methods.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ddt_magnify.h"
#include "edge_directed.h"
#include "ramp_alignment.h"
#include "user_error.h"
#include "vips_nohalo.h"

namespace bench {

namespace {

// Beyond this the peer's sampling grid is not ddtup's, and its scores would measure the shift.
const double kAlignmentTolerance = 0.01;  // input pixels

Upscaler filter(const char* name, const char* label) {
    Upscaler u;
    u.key = std::string("filter/") + name;
    u.label = label;
    u.oiio_filter = name;
    return u;
}

// `assume` none: the default's automatic choice (its key has no /assume- part).
Upscaler ddtColumn(const DdtMethod& method, const std::string& label, bool consistent,
                   std::optional<ddt::AssumedKernel> assume = std::nullopt, bool fallback = false) {
    Upscaler u;
    u.key = method.key + (consistent ? "+consistent" : "");
    if (assume) u.key += std::string("/assume-") + ddt::assumedKernelName(*assume);
    if (fallback) u.key += "+fallback";
    u.assume = assume;
    u.fallback = fallback;
    u.label = label;
    u.kind = UpscalerKind::Ddt;
    u.ddt = method;
    u.consistent = consistent;
    u.unavailable = consistent ? consistentUnavailableReason(method) : method.unavailable;
    return u;
}

std::string formatted(const char* pattern, double value) {
    char text[256];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

// A peer's column, unavailable (with the reason) when its ramp does not line up with ddtup's
// sampling; the measured shift goes into the report's notes either way.
Upscaler peerColumn(const std::string& key, const std::string& label, UpscalerKind kind, const Magnifier& magnify,
                    std::initializer_list<double> scales, std::vector<std::string>& notes) {
    Upscaler u;
    u.key = key;
    u.label = label;
    u.kind = kind;
    try {
        const double shift = rampMisalignment(magnify, scales);
        notes.push_back(label + formatted(": a magnified ramp lines up with ddtup's sampling convention within %.2g "
                                          "input pixels",
                                          shift));
        if (shift > kAlignmentTolerance) u.unavailable = formatted("misaligned by %.3f input pixels", shift);
    } catch (const std::exception& error) {
        u.unavailable = error.what();
    }
    return u;
}

}  // namespace

UpscalerSetup protocolUpscalers(const BenchDevice* device) {
    UpscalerSetup setup;
    std::vector<DdtMethod> methods = scalingMethods(device);  // CPU, then the Vulkan default variant
    const DdtMethod& cpu = methods[0];
    const DdtMethod& gpu = methods[1];
    setup.upscalers = {
        filter("triangle", "Bilinear"),
        filter("lanczos3", "Lanczos3"),
        peerColumn("vips/nohalo", "Nohalo (libvips)", UpscalerKind::Nohalo, magnifyWithNohalo, {2.0, 2.5, 4.0},
                   setup.notes),
        peerColumn("icbi", "ICBI (edge-directed)", UpscalerKind::EdgeDirected, magnifyWithIcbi, {2.0, 2.5, 4.0, 8.0},
                   setup.notes),
        ddtColumn(cpu, "CPU DDT", false),
        ddtColumn(cpu, "CPU DDT consistent", true),
        ddtColumn(gpu, "GPU DDT", false),
        ddtColumn(gpu, "GPU DDT consistent", true),
    };
    for (ddt::AssumedKernel kernel : {ddt::AssumedKernel::footprint, ddt::AssumedKernel::box, ddt::AssumedKernel::bicubic,
                                      ddt::AssumedKernel::lanczos3})
        setup.upscalers.push_back(ddtColumn(cpu, std::string("CPU consistent, ") + ddt::assumedKernelName(kernel), true, kernel));
    // The convolution fallback (--fallback lanczos3) on the default surface (the default run)
    // and on the two assumptions `mixed` mixes.
    setup.upscalers.push_back(ddtColumn(cpu, "CPU consistent + fallback", true, std::nullopt, true));
    setup.upscalers.push_back(ddtColumn(cpu, "CPU consistent, footprint + fallback", true, ddt::AssumedKernel::footprint, true));
    setup.upscalers.push_back(ddtColumn(cpu, "CPU consistent, bicubic + fallback", true, ddt::AssumedKernel::bicubic, true));
    return setup;
}

std::vector<Upscaler> selectedColumns(std::vector<Upscaler> all, const std::vector<std::string>& keys) {
    if (keys.empty()) return all;
    std::string known;
    for (const Upscaler& u : all) known += (known.empty() ? "" : ", ") + u.key;
    for (const std::string& key : keys)
        if (std::none_of(all.begin(), all.end(), [&](const Upscaler& u) { return u.key == key; }))
            throw ddt::UserError("--columns " + key + ": no such column; the columns are " + known);
    std::erase_if(all, [&](const Upscaler& u) {
        return u.key != "filter/lanczos3" && std::find(keys.begin(), keys.end(), u.key) == keys.end();
    });
    return all;
}

}  // namespace bench
