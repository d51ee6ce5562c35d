#include "ddtup_run.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "classify.h"

namespace fuzz {

namespace {

namespace fs = std::filesystem;

std::string readAll(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// The sanitizers write into files named here rather than stderr, because ddtup points
// stderr at /dev/null while a codec runs (to silence libpng), and a report made inside a
// decoder would vanish. allocator_may_return_null: a header claiming a huge image gets
// ddtup's refusal rather than the sanitizer's out-of-memory abort. The exit code tells a
// sanitizer's end from ddtup's own codes. The options the fuzzer was given come first and
// ours after them, where they win: the suite's run keeps its suppressions and preload.
std::vector<std::string> sanitizerEnvironment(const fs::path& folder) {
    const std::string log = (folder / "sanitizer").string();
    auto options = [](const char* name, const std::string& ours) {
        const char* inherited = std::getenv(name);
        return std::string(name) + "=" + (inherited && *inherited ? std::string(inherited) + ":" : "") + ours;
    };
    return {options("ASAN_OPTIONS", "allocator_may_return_null=1:detect_leaks=1:exitcode=86:log_path=" + log),
            options("UBSAN_OPTIONS", "print_stacktrace=1:halt_on_error=1:exitcode=86:log_path=" + log),
            options("LSAN_OPTIONS", "exitcode=86:log_path=" + log)};
}

// The sanitizer logs of the run, and sanitizer lines that reached stderr anyway.
std::string sanitizerReport(const fs::path& folder, const std::string& stderr_text) {
    std::string report;
    for (const auto& entry : fs::directory_iterator(folder))
        if (entry.path().filename().string().starts_with("sanitizer")) report += readAll(entry.path());
    for (const char* marker : {"ERROR: AddressSanitizer", "runtime error:", "ERROR: LeakSanitizer"})
        if (stderr_text.find(marker) != std::string::npos) report += stderr_text;
    return report;
}

// Whether the sanitizer report is nothing but LeakSanitizer's tracer failing to stop the
// threads (its fatal error names the tracer's signal); a real report has its own lines.
bool onlyTracerCrash(const std::string& report) {
    return report.find("Tracer caught signal") != std::string::npos &&
           report.find("LeakSanitizer has encountered a fatal error") != std::string::npos &&
           report.find("ERROR: LeakSanitizer: detected") == std::string::npos &&
           report.find("ERROR: AddressSanitizer") == std::string::npos && report.find("runtime error:") == std::string::npos;
}

// The name ddtup gives the output of `input` (with -f tif).
std::string outputNameOf(const std::string& input) { return fs::path(input).stem().string() + ".tif"; }

BatchResult runOnce(const RunSettings& settings, const std::vector<std::string>& inputs, const std::string& folder) {
    const fs::path out = fs::path(folder) / "out";
    fs::create_directories(out);
    BatchResult result;
    // The decoders are the target, not the optimizer or the device: the serial CPU backend
    // and a small scale keep each image quick. Every output is TIFF, which holds any depth
    // and channel layout: ddtup opens the output before it decodes the input, so an output
    // format that cannot take the input (OIIO 2.4 writes no PFM) would keep the decoder
    // from ever running.
    result.command = {settings.ddtup, "--backend", "cpu", "-q", "-s", "2", "--progress=json", "-f", "tif"};
    result.command.insert(result.command.end(), inputs.begin(), inputs.end());
    result.command.insert(result.command.end(), {"-o", out.string()});
    const fs::path stderr_path = fs::path(folder) / "stderr.txt";
    const double limit = settings.seconds_per_input * (1.0 + 0.1 * double(inputs.size()));
    result.process = runProcess(result.command, sanitizerEnvironment(folder), stderr_path.string(), limit);
    result.events = readAll(stderr_path);
    result.sanitizer_report = sanitizerReport(folder, result.events);
    result.process_fault = processFault(result.process, result.sanitizer_report);
    for (const std::string& input : inputs)
        result.outcomes.push_back(result.process_fault
                                      ? *result.process_fault
                                      : inputOutcome(result.events, input, out.string(), outputNameOf(input)));
    return result;
}

}  // namespace

BatchResult runDdtup(const RunSettings& settings, const std::vector<std::string>& inputs, const std::string& folder) {
    BatchResult result = runOnce(settings, inputs, folder);
    if (!onlyTracerCrash(result.sanitizer_report)) return result;
    result = runOnce(settings, inputs, (fs::path(folder) / "again").string());
    result.tracer_rerun = true;
    return result;
}

BatchResult runAlone(const RunSettings& settings, const std::string& input, const std::string& folder) {
    BatchResult alone = runDdtup(settings, {input}, folder);
    if (alone.outcomes.front() != Outcome::Hang) return alone;
    RunSettings patient = settings;
    patient.seconds_per_input *= 30;
    alone = runDdtup(patient, {input}, (fs::path(folder) / "longer").string());
    alone.given_longer = true;
    return alone;
}

}  // namespace fuzz
