// Everything the command line can set, filled by parseCommandLine and validated before any
// work starts.
#pragma once

#include <cstdint>
#include <string>

namespace ddt {

struct Settings {
    std::string input;
    std::string output;
    double scale = 0.0;       // 0: not given
    uint32_t width = 0;       // 0: not given
    uint32_t height = 0;      // 0: not given
    std::string backend = "vulkan";
    std::string variant;       // flip rule of the Vulkan backend; "" = the default
    int device = -1;           // Vulkan device index; -1 = choose
    bool active_set = true;    // Vulkan: re-test only edges a flip may have changed
    bool list_devices = false;
    bool stats = false;
    bool quiet = false;
};

}  // namespace ddt
