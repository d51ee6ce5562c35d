#include "machine.h"

#include <OpenImageIO/imageio.h>

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <thread>

namespace bench {

namespace {

std::string cpuModel() {
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string line;
    while (std::getline(cpuinfo, line))
        if (line.rfind("model name", 0) == 0) {
            const size_t colon = line.find(':');
            if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
        }
    return "unknown CPU";
}

std::string nowUtc() {
    const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

}  // namespace

MachineInfo describeMachine() {
    MachineInfo info;
    info.cpu_model = cpuModel();
    info.hardware_threads = std::thread::hardware_concurrency();
    info.oiio_threads = 0;
    OIIO::getattribute("threads", info.oiio_threads);
    const char* lp_threads = std::getenv("LP_NUM_THREADS");
    info.lp_num_threads = lp_threads ? lp_threads : "";
    info.oiio_version = OIIO_VERSION_STRING;
    info.compiler = __VERSION__;
#ifdef NDEBUG
    info.build = "optimised";
#else
    info.build = "with assertions";
#endif
    info.ddtup_version = DDTUP_VERSION;
    info.started_utc = nowUtc();
    return info;
}

}  // namespace bench
