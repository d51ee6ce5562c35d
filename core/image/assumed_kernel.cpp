#include "assumed_kernel.h"

#include <cmath>

namespace ddt {

namespace {

constexpr double kPi = 3.14159265358979323846;

double sinc(double x) { return x == 0.0 ? 1.0 : std::sin(kPi * x) / (kPi * x); }

const AssumedKernel kAll[] = {AssumedKernel::mixed, AssumedKernel::footprint, AssumedKernel::box,
                              AssumedKernel::bicubic, AssumedKernel::lanczos3};

}  // namespace

const char* assumedKernelName(AssumedKernel kernel) {
    switch (kernel) {
    case AssumedKernel::mixed: return "mixed";
    case AssumedKernel::footprint: return "footprint";
    case AssumedKernel::box: return "box";
    case AssumedKernel::bicubic: return "bicubic";
    case AssumedKernel::lanczos3: return "lanczos3";
    }
    return "";
}

AssumedKernel automaticAssumption(const std::string& format_name) {
    return format_name == "jpeg" ? AssumedKernel::footprint : AssumedKernel::mixed;
}

std::optional<AssumedKernel> parseAssumedKernel(const std::string& name) {
    for (AssumedKernel kernel : kAll)
        if (name == assumedKernelName(kernel)) return kernel;
    return std::nullopt;
}

std::string assumedKernelNames() {
    std::string names;
    for (AssumedKernel kernel : kAll) names += (names.empty() ? "" : ", ") + std::string(assumedKernelName(kernel));
    return names;
}

double kernelWeight(AssumedKernel kernel, double x) {
    const double a = std::fabs(x);
    switch (kernel) {
    case AssumedKernel::footprint: return std::exp(-x * x / (2.0 * kFootprintSigma * kFootprintSigma));
    case AssumedKernel::box: return a < 0.5 ? 1.0 : a == 0.5 ? 0.5 : 0.0;  // a tap on the edge counts half
    case AssumedKernel::bicubic: {
        const double k = -0.5;
        if (a < 1.0) return ((k + 2.0) * a - (k + 3.0)) * a * a + 1.0;
        if (a < 2.0) return ((k * a - 5.0 * k) * a + 8.0 * k) * a - 4.0 * k;
        return 0.0;
    }
    case AssumedKernel::lanczos3: return a < 3.0 ? sinc(x) * sinc(x / 3.0) : 0.0;
    case AssumedKernel::mixed: break;  // not one kernel (degradationTaps mixes two)
    }
    return 0.0;
}

double kernelSupport(AssumedKernel kernel) {
    switch (kernel) {
    case AssumedKernel::footprint: return 3.0 * kFootprintSigma;  // truncated at 3σ
    case AssumedKernel::box: return 0.5;
    case AssumedKernel::bicubic: return 2.0;
    case AssumedKernel::lanczos3: return 3.0;
    case AssumedKernel::mixed: break;
    }
    return 0.0;
}

}  // namespace ddt
