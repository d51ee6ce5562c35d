// Every raw measurement of a bench run: what the tables, plots and JSON are made from.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ddt_timing.h"
#include "low_res_protocols.h"
#include "machine.h"
#include "methods.h"
#include "metrics.h"
#include "overshoot.h"
#include "protocol_methods.h"

namespace bench {

// One original at one factor, reconstructed by every method.
struct ImageResult {
    std::string set;
    std::string name;
    uint32_t factor = 0;
    uint32_t width = 0, height = 0;                     // the original, after cropping to the factor
    uint32_t low_width = 0, low_height = 0;             // the input every method magnifies
    std::map<std::string, ddt::QualityScores> quality;  // by method key: filters and DDT
    std::map<std::string, DdtMeasurement> ddt;          // by DDT method key
    std::map<std::string, double> filter_seconds;       // one resize each, for information
};

// One Fig. 13 input magnified ×4 by one method.
struct ScalingResult {
    std::string dataset;  // "resized": one image at many sizes; "set": every original
    std::string image;
    uint32_t width = 0, height = 0;  // the input's size
    std::string method_key;
    DdtMeasurement measurement;
};

// One method's scores on one image of the protocol tables.
struct MethodScores {
    ddt::QualityScores quality;
    double gmsd = 0.0;
    Overshoot overshoot;  // against the method's low-resolution input
};

// One original under one protocol at one factor, magnified by every protocol-table method.
struct ProtocolImageResult {
    std::string protocol;  // Protocol::key
    Magnification factor;
    std::string set;
    std::string name;
    uint32_t width = 0, height = 0;          // the original, after cropping to the factor
    uint32_t low_width = 0, low_height = 0;  // the input every method magnifies
    std::map<std::string, MethodScores> scores;  // by Upscaler::key; absent: n/a here
};

struct BenchResults {
    MachineInfo machine;
    bool quick = false;
    uint32_t warmups = 0, repeats = 0, scaling_repeats = 0;
    std::vector<std::string> set_names;
    std::vector<uint32_t> factors;
    std::vector<DdtMethod> columns;          // Tables 1 and 3: CPU DDT and the GPU variants
    std::vector<BenchDevice> devices;        // Table 2's rows
    std::vector<DdtMethod> device_methods;   // Table 2: the GPU variants on every device
    std::vector<DdtMethod> scaling_methods;  // Fig. 13
    std::string scaling_image;
    std::vector<ImageResult> images;
    std::vector<ScalingResult> scaling;
    bool paper_tables = true;           // Tables 1–3 and Fig. 13 were run
    std::vector<Protocol> protocols;    // the protocol tables' protocols; empty: not run
    std::vector<Upscaler> upscalers;    // their columns
    std::vector<ProtocolImageResult> protocol_images;
    std::vector<std::string> notes;  // remarks for the report (dropped alpha, missing fonts …)
    double wall_seconds = 0.0;
};

}  // namespace bench
