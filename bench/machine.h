// What the timings were measured on, for the report and the raw measurements.
#pragma once

#include <string>

namespace bench {

struct MachineInfo {
    std::string cpu_model;       // /proc/cpuinfo's "model name"
    unsigned hardware_threads;   // std::thread::hardware_concurrency()
    int oiio_threads;            // OIIO's pool, used by the filters and the protocol (untimed)
    std::string lp_num_threads;  // lavapipe's worker threads (LP_NUM_THREADS), "" if unset
    std::string oiio_version;
    std::string compiler;  // __VERSION__
    std::string build;     // "optimised" or "with assertions" (NDEBUG)
    std::string ddtup_version;
    std::string started_utc;  // ISO 8601
};

MachineInfo describeMachine();

}  // namespace bench
