// ddtup: magnify images by data-dependent triangulation.
#include <malloc.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <optional>
#include <string>

#include "allocation_watch.h"
#include "backend_factory.h"
#include "buffer.h"
#include "batch_plan.h"
#include "cli.h"
#include "codec_module.h"
#include "context.h"
#include "exit_codes.h"
#include "image_file.h"
#include "parallel.h"
#include "pipeline.h"
#include "reporter.h"
#include "temp_files.h"
#include "volume/volume_job.h"

namespace {

double mebibytes(uint64_t bytes) { return double(bytes) / double(1 << 20); }

// The process's memory so far: in a batch, of every job up to this one.
void printMemory(bool batch) {
    const char* so_far = batch ? ", the batch so far" : "";
    std::printf("memory-peak    %.1f MiB  (resident%s)\n", mebibytes(ddt::peakResidentBytes()), so_far);
    if (const std::optional<uint64_t> block = ddt::largestHostBlock())
        std::printf("memory-block   %.1f MiB  (the largest block allocated%s)\n", mebibytes(*block), so_far);
    if (const uint64_t buffer = ddt::largestDeviceBuffer())
        std::printf("device-block   %.1f MiB  (the largest device buffer%s)\n", mebibytes(buffer), so_far);
}

void printStats(const ddt::ImageJob& job, bool batch) {
    const ddt::JobReport& report = job.report();
    const ddt::OptimizeStats& s = report.stats;
    if (batch) std::printf("input          %s\n", job.task().input.c_str());
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
    if (const auto& simplify = report.simplify) {
        std::printf("vertices       %u -> %u", simplify->vertices_before, simplify->vertices_after);
        if (simplify->rounds) std::printf("  (the parallel rule on the device, %u rounds)\n", simplify->rounds);
        else std::printf("  (the serial greedy simplifier)\n");
    }
    std::printf("time-init      %.3f s  (read the image)\n", report.times.init_s);
    std::printf("time-comp      %.3f s  (build the mesh, upload, optimize%s%s)\n", report.times.comp_s,
                report.simplify ? ", simplify" : "",
                !report.delaunay_on_device      ? ""
                : *report.delaunay_on_device ? "; the samples triangulated on the Vulkan device"
                                             : "; the samples triangulated on the CPU");
    if (report.times.reconstruct_s > 0.0)
        std::printf("time-recon     %.3f s  (the consistent reconstruction, assuming %s)\n", report.times.reconstruct_s,
                    report.assumed ? ddt::assumedKernelName(*report.assumed) : "?");
    std::printf("time-final     %.3f s  (render + save image; the paper's time-final saved the mesh)\n",
                report.times.final_s);
    std::printf("time-sum       %.3f s\n",
                report.times.init_s + report.times.comp_s + report.times.reconstruct_s + report.times.final_s);
    printMemory(batch);
    if (batch) std::printf("\n");
    std::fflush(stdout);
}

void printVolumeStats(const ddt::ImageTask& task, const ddt::VolumeReport& report, bool batch) {
    const ddt::TetLawsonStats& s = report.stats.lawson;
    if (batch) std::printf("input          %s\n", task.input.c_str());
    std::printf("volume         %u x %u x %u -> %u x %u x %u\n", report.in[0], report.in[1], report.in[2], report.out[0],
                report.out[1], report.out[2]);
    std::printf("bricks         %u\n", report.stats.bricks);
    std::printf("tets           %llu -> %llu\n", static_cast<unsigned long long>(report.stats.tets_before),
                static_cast<unsigned long long>(report.stats.tets_after));
    std::printf("cost-init      %.9g\n", s.cost_before);
    std::printf("cost-final     %.9g\n", s.cost_after);
    std::printf("flips          %llu  (", static_cast<unsigned long long>(s.flipCount()));
    for (uint32_t kind = 0; kind < ddt::kFlipKindCount; ++kind)
        std::printf("%s%s %llu", kind ? ", " : "", ddt::flipKindName(ddt::FlipKind(kind)),
                    static_cast<unsigned long long>(s.flips[kind]));
    std::printf(")\n");
    std::printf("%s     %u%s\n", report.on_device ? "rounds    " : "iterations", s.iterations,
                s.capped ? " (safety cap reached)" : "");
    std::printf("time-init      %.3f s  (read the volume)\n", report.read_s);
    std::printf("time-comp      %.3f s  (build the tetrahedral meshes, optimize: %s)\n", report.stats.optimize_s,
                report.on_device ? "the parallel rule on the Vulkan device" : "the serial generalized Lawson, CPU");
    std::printf("time-resample  %.3f s  (each output voxel in its tetrahedron%s)\n", report.stats.resample_s,
                report.on_device ? ", on the Vulkan device" : "");
    std::printf("time-final     %.3f s  (write the volume%s)\n", report.write_s, "");
    std::printf("time-sum       %.3f s\n", report.read_s + report.stats.optimize_s + report.stats.resample_s + report.write_s);
    printMemory(batch);
    if (batch) std::printf("\n");
    std::fflush(stdout);
}

void printDevices() {
    for (const ddt::DeviceInfo& d : ddt::listDevices()) {
        std::printf("%u: %s (%s, %s, %.1f GiB)%s%s\n", d.index, d.name.c_str(), ddt::deviceTypeName(d.type),
                    d.driver.c_str(), double(d.memory_bytes) / (1u << 30), d.unusable.empty() ? "" : " — unusable: ",
                    d.unusable.c_str());
    }
}

// One thread count for every pool in the process: ddtup's own (optimizing, rendering,
// encoding), OIIO's (decoding) and lavapipe's, unless its LP_NUM_THREADS is set. Decoding
// the next image is short beside the rest, and rendering and encoding share ddtup's pool, so
// the process stays near that many busy threads; a batch script running several ddtup
// processes divides the processors with --threads.
void sizeThreadPools(unsigned threads) {
    ddt::setThreadCount(threads);
    const int count = int(ddt::threadCount());
    ddt::setCodecThreads(unsigned(count));
    ::setenv("LP_NUM_THREADS", std::to_string(count).c_str(), 0);
}

// Tiles and the reconstruction allocate and free arrays of megabytes again and again. By
// default glibc maps each large one afresh and unmaps it when freed, and the kernel zeroes
// every page on first touch. Kept in the heap, freed arrays are reused instead. Measured
// (perf stat, /usr/bin/time) on a 1600×1112 photo at ×4: 230 000 → 48 000–62 000 page
// faults, 0.8 → 0.28 s of system time, 3.2 → 2.9 s; the price is the peak resident size,
// 248 → 269 MB (512² at ×8: 257 → 271 MB), as freed blocks stay with the process. One heap
// (arena) for every thread, not one per thread, so that a block one thread frees is reused by
// the others instead of each heap keeping its own: the photo's peak 284 → 275 MiB, no slower
// (farm-bench, 5 pairs); the hot loops do not allocate.
void keepFreedMemoryForReuse() {
    ::mallopt(M_MMAP_THRESHOLD, 32 << 20);   // blocks below 32 MiB (glibc's most) come from the heap
    ::mallopt(M_TRIM_THRESHOLD, 256 << 20);  // and up to 256 MiB free at its top stays there
    ::mallopt(M_ARENA_MAX, 1);
}

int run(const ddt::Settings& settings, ddt::Reporter& reporter) {
    std::vector<ddt::ImageTask> tasks;
    try {
        tasks = ddt::planBatch(settings);
    } catch (const ddt::UserError& error) {
        reporter.fatal(error.what(), ddt::kExitSomeFailed);
        return reporter.finish();
    }
    reporter.start(tasks.size());
    bool any_image = false, any_volume = false;
    for (size_t i = 0; i < tasks.size(); ++i) {
        if (tasks[i].state == ddt::ImageTask::State::Skipped) reporter.skipped(i, tasks[i]);
        if (tasks[i].state == ddt::ImageTask::State::Refused) reporter.failed(tasks[i].input, tasks[i].reason);
        const bool ready = tasks[i].state == ddt::ImageTask::State::Ready;
        (tasks[i].volume ? any_volume : any_image) |= ready;
    }

    ddt::ChosenBackend chosen;
    auto backend = [&]() -> ddt::Backend* {
        try {
            chosen = ddt::makeBackend(settings);
        } catch (const ddt::UserError& error) {
            reporter.fatal(error.what(), ddt::kExitNoDevice);
            return nullptr;
        }
        reporter.backend(chosen.choice);
        return chosen.backend.get();
    };
    std::mutex stats_mutex;
    const bool batch = tasks.size() > 1;
    if (any_image)
        ddt::runPipeline(tasks, settings, backend, reporter, [&](const ddt::ImageJob& job) {
            if (!settings.stats) return;
            std::lock_guard lock(stats_mutex);
            printStats(job, batch);
        });
    if (any_volume)
        ddt::runVolumeTasks(tasks, settings, reporter, [&](const ddt::ImageTask& task, const ddt::VolumeReport& report) {
            if (settings.stats) printVolumeStats(task, report, batch);
        });
    return reporter.finish();
}

}  // namespace

int main(int argc, char** argv) {
    keepFreedMemoryForReuse();
    ddt::installInterruptCleanup();
    int exit_code = 0;
    std::optional<ddt::Settings> settings = ddt::parseCommandLine(argc, argv, exit_code);
    if (!settings) return exit_code;
    sizeThreadPools(settings->threads);
    if (settings->list_devices) {
        try {
            printDevices();
            return ddt::kExitDone;
        } catch (const ddt::UserError& error) {
            std::fprintf(stderr, "ddtup: %s\n", error.what());
            return ddt::kExitNoDevice;
        }
    }
    ddt::Reporter reporter(*settings);
    try {
        return run(*settings, reporter);
    } catch (const std::exception& error) {
        // A bug, not a user error; still one line instead of std::terminate's abort.
        reporter.fatal(std::string("internal error: ") + error.what(), ddt::kExitInternal);
        return reporter.finish();
    }
}
