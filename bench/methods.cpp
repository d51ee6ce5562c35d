#include "methods.h"

#include <cassert>

#include "context.h"
#include "backend_factory.h"

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

DdtMethod cpuMethod() { return {"cpu", "CPU DDT", "cpu", "", "", ""}; }

DdtMethod gpuMethod(const std::string& variant, const std::string& label, const BenchDevice* device) {
    DdtMethod method;
    method.backend = "vulkan";
    method.variant = variant;
    method.label = label;
    method.device = device ? device->id : "";
    method.key = "vulkan/" + (variant.empty() ? std::string("default") : variant) + "/" + method.device;
    method.unavailable = device ? "" : "no usable Vulkan device";
    return method;
}

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

std::vector<DdtMethod> ddtMethods(const BenchDevice* device) {
    std::vector<DdtMethod> methods = {cpuMethod()};
    for (const GpuVariant& variant : kGpuVariants) methods.push_back(gpuMethod(variant.name, variant.label, device));
    return methods;
}

std::vector<DdtMethod> scalingMethods(const BenchDevice* device) {
    return {cpuMethod(), gpuMethod("", "GPU default variant", device),
            gpuMethod("exproi-maxgain", "GPU ExpROI MaxGain", device)};
}

std::unique_ptr<ddt::Backend> makeMethodBackend(const DdtMethod& method) {
    assert(method.unavailable.empty());
    ddt::Settings settings;
    settings.backend = method.backend;
    settings.variant = method.variant;
    settings.device = method.device.empty() ? -1 : std::stoi(method.device);
    return ddt::makeBackend(settings).backend;
}

}  // namespace bench
