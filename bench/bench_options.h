// Everything the bench's command line can set, filled by parseBenchCommandLine and checked
// before any work starts.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

struct BenchOptions {
    std::vector<std::string> data_dirs;  // one set per folder; default: the bundled two
    std::string out_dir = "bench-results";
    std::vector<uint32_t> factors = {4, 8};
    uint32_t warmups = 1;        // untimed runs of every DDT method before the timed ones
    uint32_t repeats = 5;        // timed runs; tables report the median
    std::string device = "all";  // Vulkan devices for the GPU columns: "all" or one id
    std::string scaling_image;   // Fig. 13's resized image; default: the first set's first
    uint32_t scaling_max_side = 2048;
    uint32_t scaling_repeats = 3;
    std::string tables = "all";   // "paper" (Tables 1–3, Fig. 13), "protocols" (bench/README.md) or "all"
    std::string protocol_filter;  // an OIIO filter for the held-back protocol C; "": none
    std::vector<std::string> columns;  // the protocol tables' columns by key, with Lanczos3; empty: all
    bool quick = false;  // CI: two small crops, one factor, one repeat, small Fig. 13
};

}  // namespace bench
