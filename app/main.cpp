// ddtup: magnify images by data-dependent triangulation.
#include <cstdio>
#include <iostream>
#include <new>

#include "cli.h"
#include "context.h"
#include "temp_files.h"
#include "upscale_job.h"

namespace {

void printStats(const ddt::JobReport& report) {
    const ddt::OptimizeStats& s = report.stats;
    std::printf("output         %u x %u\n", report.out.width, report.out.height);
    std::printf("cost-init      %.6f\n", s.cost_init);
    std::printf("cost-final     %.6f\n", s.cost_final);
    std::printf("improvement    %.3f %%\n", s.improvement());
    std::printf("flips          %llu\n", static_cast<unsigned long long>(s.flips));
    std::printf("iterations     %u%s\n", s.iterations, s.capped ? " (safety cap reached)" : "");
    if (s.rounds) std::printf("rounds         %llu (at most %u in one iteration)\n", static_cast<unsigned long long>(s.rounds),
                              s.max_rounds_in_iteration);
    if (s.dispatches) std::printf("dispatches     %llu\n", static_cast<unsigned long long>(s.dispatches));
    if (s.device_ms > 0.0) std::printf("device-comp    %.3f s  (GPU timestamps)\n", s.device_ms * 1e-3);
    std::printf("time-init      %.3f s  (load + build mesh)\n", report.times.init_s);
    std::printf("time-comp      %.3f s  (optimize)\n", report.times.comp_s);
    std::printf("time-final     %.3f s  (render + save image; the paper's time-final saved the mesh)\n",
                report.times.final_s);
    std::printf("time-sum       %.3f s\n", report.times.init_s + report.times.comp_s + report.times.final_s);
}

void printDevices() {
    for (const ddt::DeviceInfo& d : ddt::listDevices()) {
        std::printf("%u: %s (%s, %s, %.1f GiB)%s%s\n", d.index, d.name.c_str(), ddt::deviceTypeName(d.type),
                    d.driver.c_str(), double(d.memory_bytes) / (1u << 30), d.unusable.empty() ? "" : " — unusable: ",
                    d.unusable.c_str());
    }
}

int run(const ddt::Settings& settings) {
    try {
        if (settings.list_devices) {
            printDevices();
            return 0;
        }
        ddt::JobReport report = ddt::runUpscaleJob(settings);
        if (!settings.quiet)
            for (const std::string& note : report.notes) std::cerr << "ddtup: note: " << note << "\n";
        if (settings.stats) printStats(report);
        return 0;
    } catch (const ddt::UserError& error) {
        std::cerr << "ddtup: " << error.what() << "\n";
        return 1;
    } catch (const std::bad_alloc&) {
        std::cerr << "ddtup: " << settings.input << ": out of memory\n";
        return 1;
    } catch (const std::exception& error) {
        // A bug, not a user error; still one line instead of std::terminate's abort.
        std::cerr << "ddtup: internal error: " << error.what() << "\n";
        return 1;
    }
}

}  // namespace

int main(int argc, char** argv) {
    ddt::installInterruptCleanup();
    int exit_code = 0;
    std::optional<ddt::Settings> settings = ddt::parseCommandLine(argc, argv, exit_code);
    if (!settings) return exit_code;
    return run(*settings);
}
