// What the bench compares: the classic OIIO filters and the DDT methods. A DDT method is one
// (backend, variant, device) entry; the tables get one column per entry, and an entry that
// cannot run here is listed with the reason and reported as "n/a".
//
// Wiring a backend in: ddtMethods() lists the entries and makeMethodBackend() builds them;
// benchDevices() is the device list Table 2 runs over. Nothing else needs to change.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "backend.h"

namespace bench {

struct FilterMethod {
    std::string key;    // unique id in the raw measurements: "filter/triangle"
    std::string label;  // column heading, as the paper names it
    std::string oiio_name;
};

// Bilinear, b-spline and Lanczos as in the paper's Table 3, plus Catmull-Rom.
const std::vector<FilterMethod>& filterMethods();

struct BenchDevice {
    std::string id;    // what --device selects and DdtMethod::device holds
    std::string name;  // as the driver reports it
};

// The usable Vulkan devices `selection` picks ("all", or one index from --list-devices);
// none when no Vulkan driver is installed. Table 2 has a row per device.
std::vector<BenchDevice> benchDevices(const std::string& selection);

struct DdtMethod {
    std::string key;          // unique id in the raw measurements: "cpu", "vulkan/maxgain/0", "cpu/variance"
    std::string label;        // column heading, as the paper names it: "GPU MaxGain"
    std::string backend;      // "cpu" or "vulkan"
    std::string variant;      // Vulkan variant ("basic", "exproi-maxgain", …); "" = default
    std::string device;       // BenchDevice::id; "" for the CPU
    std::string unavailable;  // "" if it runs here, else why it is reported as n/a
    ddt::CostFunction cost = ddt::CostFunction::sederberg;  // the cost the flips lower
};

// The DDT methods on `device` (null: no Vulkan device): the CPU reference, then every GPU
// variant of the paper's Tables 1–3 and the later ones, in the paper's column order, all with
// Sederberg's cost; then, for Tóth et al.'s content-weighted costs (variance, face-SCF), the
// CPU reference and the Vulkan backend's default variant.
std::vector<DdtMethod> ddtMethods(const BenchDevice* device);

// The CPU reference's key for `cost` ("cpu" for Sederberg's): the method a column's costs are
// compared with, since costs of different functions do not compare.
std::string cpuKeyFor(ddt::CostFunction cost);

// Fig. 13's methods: the CPU reference, the Vulkan backend's default variant and ExpROI
// MaxGain (the paper's choice).
std::vector<DdtMethod> scalingMethods(const BenchDevice* device);

// A fresh backend for an available method.
std::unique_ptr<ddt::Backend> makeMethodBackend(const DdtMethod& method);

}  // namespace bench
