#include "methods.h"

#include <cassert>

#include "backend_factory.h"
#include "context.h"
#include "flip_rule.h"
#include "vulkan_backend.h"

namespace bench {

namespace {

struct GpuVariant {
    const char* name;   // the Vulkan backend's variant name
    const char* label;  // the paper's column heading
};

// The paper's Table 1 columns (Sec. 5: ExpROI, MaxGain, ExpROI_N for the first N
// iterations), then the variants added after it.
const GpuVariant kGpuVariants[] = {
    {"basic", "GPU basic"},
    {"exproi", "GPU ExpROI"},
    {"maxgain", "GPU MaxGain"},
    {"exproi-maxgain", "GPU ExpROI MaxGain"},
    {"exproi2-maxgain", "GPU ExpROI2 MaxGain"},
    {"exproi3-maxgain", "GPU ExpROI3 MaxGain"},
    {"exproi4-maxgain", "GPU ExpROI4 MaxGain"},
    {"localmax", "GPU LocalMax"},
    {"exproi-localmax", "GPU ExpROI LocalMax"},
};

// The label's suffix for a content-weighted cost: " variance", " face-SCF"; "" for Sederberg's.
std::string costSuffix(ddt::CostFunction cost) {
    if (cost == ddt::CostFunction::variance) return " variance";
    if (cost == ddt::CostFunction::face_scf) return " face-SCF";
    return "";
}

DdtMethod cpuMethod(ddt::CostFunction cost = ddt::CostFunction::sederberg) {
    DdtMethod method;
    method.key = cpuKeyFor(cost);
    method.label = "CPU DDT" + costSuffix(cost);
    method.backend = "cpu";
    method.cost = cost;
    return method;
}

DdtMethod gpuMethod(const std::string& variant, const std::string& label, const BenchDevice* device,
                    ddt::CostFunction cost = ddt::CostFunction::sederberg) {
    DdtMethod method;
    method.backend = "vulkan";
    method.variant = variant;
    method.label = label + costSuffix(cost);
    method.device = device ? device->id : "";
    method.cost = cost;
    // Sederberg's keys are those of the earlier measurements; other costs add theirs.
    const std::string name = (variant.empty() ? std::string("default") : variant) +
                             (cost == ddt::CostFunction::sederberg ? "" : std::string("+") + ddt::costFunctionName(cost));
    method.key = "vulkan/" + name + "/" + method.device;
    method.unavailable = device ? "" : "no usable Vulkan device";
    return method;
}

const ddt::CostFunction kContentCosts[] = {ddt::CostFunction::variance, ddt::CostFunction::face_scf};

}  // namespace

const std::vector<FilterMethod>& filterMethods() {
    static const std::vector<FilterMethod> filters = {
        {"filter/triangle", "Bilinear filter", "triangle"},
        {"filter/bspline", "b-spline filter", "bspline"},
        {"filter/lanczos3", "Lanczos filter", "lanczos3"},
        {"filter/catmull-rom", "Catmull-Rom filter", "catmull-rom"},
    };
    return filters;
}

std::vector<BenchDevice> benchDevices(const std::string& selection) {
    std::vector<BenchDevice> devices;
    try {
        for (const ddt::DeviceInfo& info : ddt::listDevices()) {
            const std::string id = std::to_string(info.index);
            if (info.unusable.empty() && (selection == "all" || selection == id)) devices.push_back({id, info.name});
        }
    } catch (const ddt::UserError&) {
        // No Vulkan driver: the GPU columns are reported as n/a.
    }
    return devices;
}

std::string cpuKeyFor(ddt::CostFunction cost) {
    return cost == ddt::CostFunction::sederberg ? "cpu" : std::string("cpu/") + ddt::costFunctionName(cost);
}

std::vector<DdtMethod> ddtMethods(const BenchDevice* device) {
    std::vector<DdtMethod> methods = {cpuMethod()};
    for (const GpuVariant& variant : kGpuVariants) methods.push_back(gpuMethod(variant.name, variant.label, device));
    for (ddt::CostFunction cost : kContentCosts) {
        methods.push_back(cpuMethod(cost));
        methods.push_back(gpuMethod(ddt::kDefaultFlipRule, "GPU default variant", device, cost));
    }
    return methods;
}

std::vector<DdtMethod> scalingMethods(const BenchDevice* device) {
    return {cpuMethod(), gpuMethod("", "GPU default variant", device),
            gpuMethod("exproi-maxgain", "GPU ExpROI MaxGain", device)};
}

std::unique_ptr<ddt::Backend> makeMethodBackend(const DdtMethod& method) {
    assert(method.unavailable.empty());
    // The content-weighted costs are built here until app's Settings carries the cost.
    if (method.cost != ddt::CostFunction::sederberg) {
        if (method.backend == "cpu") {
            ddt::LawsonOptions options;
            options.cost = method.cost;
            return ddt::makeCpuBackend(options);
        }
        ddt::VulkanOptions options;
        if (!method.variant.empty()) options.rule = method.variant;
        options.cost = method.cost;
        options.device_index = method.device.empty() ? -1 : std::stoi(method.device);
        return ddt::makeVulkanBackend(options);
    }
    ddt::Settings settings;
    settings.backend = method.backend;
    settings.variant = method.variant;
    settings.device = method.device.empty() ? -1 : std::stoi(method.device);
    return ddt::makeBackend(settings).backend;
}

}  // namespace bench
