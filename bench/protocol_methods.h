// The columns of the protocol tables: OIIO's bilinear and Lanczos3, the peers libvips'
// Nohalo and the edge-directed ICBI (edge_directed.h), and DDT plain and consistent on the CPU
// and on the Vulkan backend's default variant, and the CPU's consistent surface assuming each
// named resize filter (`--assume`), and the convolution fallback (`--fallback lanczos3`) on
// the default and on the bicubic assumption. Availability is probed once, up front: a column that cannot
// run here (no Vulkan device, a peer misaligned) keeps its place as "n/a" with the reason.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "assumed_kernel.h"
#include "methods.h"

namespace bench {

enum class UpscalerKind { OiioFilter, Nohalo, EdgeDirected, Ddt };

struct Upscaler {
    std::string key;    // unique in the raw measurements: "filter/lanczos3", "cpu+consistent" …
    std::string label;  // column heading
    UpscalerKind kind = UpscalerKind::OiioFilter;
    std::string oiio_filter;  // OiioFilter
    DdtMethod ddt;            // Ddt
    bool consistent = false;  // Ddt: the consistent reconstruction instead of the plain surface
    // Ddt, consistent: the filter it assumes; none: what ddtup's default (--assume auto)
    // assumes of the input, by its file's format (ddt::automaticAssumption).
    std::optional<ddt::AssumedKernel> assume;
    bool fallback = false;  // Ddt, consistent: blended towards Lanczos3 where contrast is low (--fallback lanczos3)
    std::string unavailable;  // "" if it runs here
};

struct UpscalerSetup {
    std::vector<Upscaler> upscalers;
    std::vector<std::string> notes;  // the peers' measured alignment
};

// Probes every peer and DDT backend; `device` null: no Vulkan device.
UpscalerSetup protocolUpscalers(const BenchDevice* device);

// The columns of `all` whose keys `keys` names (`--columns`), and Lanczos3, every table's
// reference; all of them if `keys` is empty. An unknown key is a UserError naming the known ones.
std::vector<Upscaler> selectedColumns(std::vector<Upscaler> all, const std::vector<std::string>& keys);

}  // namespace bench
