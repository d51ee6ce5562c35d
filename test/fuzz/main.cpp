// ddtup_fuzz: damaged images through the real ddtup executable, counted by format, damage
// kind and outcome. See scripts/fuzz for how CI runs it, and docs/CI.md ("Fuzzing").
//
//   ddtup_fuzz [--count N] [--seed S] [--ddtup PATH] [--out DIR] [--batch N] [--jobs N]
//              [--timeout S] [--work DIR]
//   ddtup_fuzz --replay DIR [--ddtup PATH]
//
// Every input is made from a valid seed image by one kind of damage, chosen by its number;
// its randomness comes from --seed and that number alone, so a run is reproducible and any
// input can be made again. Inputs go through ddtup in batches, one process per batch; when a
// process crashes, hangs or a sanitizer reports, each of its inputs is run again alone to
// find the culprits. Faulty inputs are kept in --out with a record, for --replay.
// Exit status: 0 when nothing was counted as a fault, 1 when something was, 2 for bad usage.
#include <CLI/CLI.hpp>
#include <stdlib.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "classify.h"
#include "damage.h"
#include "ddtup_run.h"
#include "failures.h"
#include "formats.h"
#include "report.h"

namespace {

namespace fs = std::filesystem;
using namespace fuzz;

struct Options {
    size_t count = 2400;
    uint64_t seed = 1;
    std::string ddtup = DDTUP_EXECUTABLE;
    std::string out = "fuzz-failures";
    std::string work;  // default: a temporary folder, removed at the end
    std::string replay;
    size_t batch = 40;
    unsigned jobs = 2;
    double timeout = 20;
};

// One damaged input.
struct Case {
    size_t index;
    const Format* format;
    DamageKind kind;
    std::string variant;  // of the seed it was made from
    std::string what;     // the damage, in words
    std::string path;
};

// The scratch folder: a temporary one unless --work names one (then it is kept).
class WorkFolder {
public:
    explicit WorkFolder(const std::string& path) {
        if (!path.empty()) {
            path_ = fs::absolute(path);
            fs::create_directories(path_);
            return;
        }
        std::string pattern = (fs::temp_directory_path() / "ddtup-fuzz-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder");
        path_ = pattern;
        temporary_ = true;
    }
    ~WorkFolder() {
        std::error_code ignored;
        if (temporary_) fs::remove_all(path_, ignored);
    }
    WorkFolder(const WorkFolder&) = delete;
    WorkFolder& operator=(const WorkFolder&) = delete;
    fs::path operator/(const std::string& name) const { return path_ / name; }

private:
    fs::path path_;
    bool temporary_ = false;
};

void writeFile(const fs::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out << bytes;
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::string describeProcess(const ProcessResult& process) {
    if (process.timed_out) return "timed out after " + std::to_string(int(process.seconds)) + " s";
    if (process.end_signal) return "killed by signal " + std::to_string(process.end_signal);
    return "exit code " + std::to_string(process.exit_code);
}

std::string commandLine(const std::vector<std::string>& command) {
    std::string line;
    for (const std::string& word : command) line += (line.empty() ? "" : " ") + word;
    return line;
}

// What a kept failure's .txt file says.
std::string failureRecord(const std::string& heading, Outcome outcome, const BatchResult& run) {
    return heading + "outcome of the command below: " + outcomeName(outcome) +
           "\ncommand: " + commandLine(run.command) + "\nprocess: " + describeProcess(run.process) +
           (run.given_longer ? " (a second run, given 30 times the limit)" : "") +
           "\n--- stderr (ddtup's JSON events) ---\n" + run.events + "--- sanitizer report ---\n" +
           (run.sanitizer_report.empty() ? "(none)\n" : run.sanitizer_report);
}

// Every seed must go through whole: one that does not is a fault of its own (in ddtup, or in
// the fuzzer), and would weaken the damage made from it.
int checkSeeds(const RunSettings& settings, const std::vector<std::pair<const Format*, Seed>>& seeds,
               const WorkFolder& work) {
    fs::create_directories(work / "seeds");
    std::vector<std::string> paths;
    for (const auto& [format, seed] : seeds) {
        paths.push_back((work / "seeds" / ("seed-" + format->name + "-" + seed.variant + seed.extension)).string());
        writeFile(paths.back(), seed.bytes);
    }
    const BatchResult run = runDdtup(settings, paths, (work / "seeds-run").string());
    int refused = 0;
    for (size_t i = 0; i < paths.size(); ++i)
        if (run.outcomes[i] != Outcome::Accepted) {
            ++refused;
            std::fprintf(stderr, "fuzz: seed %s: %s\n", fs::path(paths[i]).filename().c_str(),
                         outcomeName(run.outcomes[i]));
        }
    if (refused)
        std::fprintf(stderr, "fuzz: %d of %zu seed images were not accepted; ddtup's stderr:\n%s", refused,
                     paths.size(), run.events.c_str());
    return refused;
}

std::vector<Case> makeCases(const Options& options, const std::vector<std::vector<Seed>>& seeds,
                            const WorkFolder& work) {
    const std::vector<Format>& formats = allFormats();
    fs::create_directories(work / "inputs");
    std::vector<Case> cases;
    for (size_t i = 0; i < options.count; ++i) {
        // Formats and kinds in turn, so every batch mixes them and any count spreads evenly.
        const size_t f = i % formats.size();
        const DamageKind kind = kDamageKinds[(i / formats.size()) % std::size(kDamageKinds)];
        Random random = Random::forInput(options.seed, i);
        const Seed& seed = random.pick(seeds[f]);
        std::string bytes = seed.bytes;
        Case c{i, &formats[f], kind, seed.variant, "", ""};
        c.what = std::string(damageKindName(kind)) + ": " + damageFile(formats[f], kind, bytes, random);
        c.path = (work / "inputs" / caseFileName(i, formats[f].name, damageKindName(kind), seed.extension)).string();
        writeFile(c.path, bytes);
        cases.push_back(std::move(c));
    }
    return cases;
}

class Fuzzer {
public:
    Fuzzer(const Options& options, const RunSettings& settings, const WorkFolder& work)
        : options_(options), settings_(settings), work_(work) {}

    Report& report() { return report_; }
    size_t strayLines() const { return stray_lines_; }
    size_t slowInputs() const { return slow_inputs_; }
    size_t tracerReruns() const { return tracer_reruns_; }

    // Runs the cases in batches on --jobs threads.
    void run(const std::vector<Case>& cases) {
        std::atomic<size_t> next_batch = 0;
        const size_t batches = (cases.size() + options_.batch - 1) / options_.batch;
        std::vector<std::thread> threads;
        for (unsigned j = 0; j < std::max(1u, options_.jobs); ++j)
            threads.emplace_back([&] {
                for (size_t b; (b = next_batch++) < batches;) {
                    const size_t begin = b * options_.batch, end = std::min(cases.size(), begin + options_.batch);
                    runBatch(b, std::vector<Case>(cases.begin() + long(begin), cases.begin() + long(end)));
                }
            });
        for (std::thread& thread : threads) thread.join();
    }

private:
    void runBatch(size_t number, const std::vector<Case>& batch) {
        std::vector<std::string> paths;
        for (const Case& c : batch) paths.push_back(c.path);
        const fs::path folder = work_ / ("batch-" + std::to_string(number));
        const BatchResult run = runDdtup(settings_, paths, folder.string());
        int culprits = 0;
        for (size_t i = 0; i < batch.size(); ++i) {
            const Case& c = batch[i];
            Outcome outcome = run.outcomes[i];
            if (isFault(outcome)) {
                // Alone, for the record, and to find which inputs a failed process died of.
                const BatchResult alone =
                    runAlone(settings_, c.path, (folder / ("alone-" + std::to_string(i))).string());
                if (alone.given_longer || alone.tracer_rerun) {
                    std::lock_guard lock(mutex_);
                    slow_inputs_ += alone.given_longer;
                    tracer_reruns_ += alone.tracer_rerun;
                }
                if (run.process_fault) outcome = alone.outcomes.front();
                if (isFault(outcome)) {
                    ++culprits;
                    keepFailure(c, run.outcomes[i], alone);
                }
            }
            std::lock_guard lock(mutex_);
            report_.count(c.format->name, damageKindName(c.kind), outcome);
        }
        std::lock_guard lock(mutex_);
        tracer_reruns_ += run.tracer_rerun;
        if (run.process_fault && culprits == 0) {
            report_.countBatchFault();
            saveBatchFailure(options_.out, number, paths,
                             failureRecord("batch " + std::to_string(number) +
                                               ": its process failed, none of its inputs alone did\n",
                                           *run.process_fault, run));
        }
        stray_lines_ += fuzz::strayLines(run.events).size();
        // A line now and then, for logs: roughly every tenth of the run.
        const size_t step = std::max<size_t>(options_.batch, options_.count / 10);
        if ((done_ + batch.size()) / step > done_ / step)
            std::fprintf(stderr, "fuzz: %zu of %zu inputs\n", done_ + batch.size(), options_.count);
        done_ += batch.size();
        std::error_code ignored;
        fs::remove_all(folder, ignored);
    }

    void keepFailure(const Case& c, Outcome in_batch, const BatchResult& alone) {
        const Outcome outcome = alone.outcomes.front();
        const std::string heading = "input " + std::to_string(c.index) + " of ddtup_fuzz --seed " +
                                    std::to_string(options_.seed) + "\nformat: " + c.format->name + " (seed image " +
                                    c.variant + ")\ndamage: " + c.what + "\nin the batch: " + outcomeName(in_batch) +
                                    "\n";
        std::lock_guard lock(mutex_);
        saveFailure(options_.out, c.path, failureRecord(heading, outcome, alone));
        std::fprintf(stderr, "fuzz: %s: %s (%s)\n", fs::path(c.path).filename().c_str(), outcomeName(outcome),
                     c.what.c_str());
    }

    const Options& options_;
    const RunSettings& settings_;
    const WorkFolder& work_;
    std::mutex mutex_;
    Report report_;
    size_t stray_lines_ = 0;
    size_t slow_inputs_ = 0;
    size_t tracer_reruns_ = 0;  // runs made again after LeakSanitizer's tracer crashed (ddtup_run.h)
    size_t done_ = 0;
};

int replay(const Options& options, const RunSettings& settings) {
    WorkFolder work(options.work);
    Report report;
    for (const std::string& input : savedInputs(options.replay)) {
        const CaseName name = parseCaseName(input);
        const BatchResult run = runAlone(settings, input, (work / fs::path(input).filename().string()).string());
        const Outcome outcome = run.outcomes.front();
        report.count(name.format, name.kind, outcome);
        std::printf("%s: %s (%s)\n", fs::path(input).filename().c_str(), outcomeName(outcome),
                    describeProcess(run.process).c_str());
        if (isFault(outcome)) std::printf("%s%s", run.events.c_str(), run.sanitizer_report.c_str());
    }
    report.print(stdout);
    return report.faults() ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    CLI::App app("Damaged images through the real ddtup executable; exits 1 when any fault was counted");
    app.option_defaults()->multi_option_policy(
        CLI::MultiOptionPolicy::TakeLast);  // scripts/fuzz's defaults, then yours
    app.add_option("--count", options.count, "How many damaged inputs")->capture_default_str();
    app.add_option("--seed", options.seed, "Seed of the run: the same seed makes the same inputs")
        ->capture_default_str();
    app.add_option("--ddtup", options.ddtup, "The ddtup executable (built with the sanitizers)")->capture_default_str();
    app.add_option("--out", options.out, "Folder for the faulty inputs and their records")->capture_default_str();
    app.add_option("--work", options.work, "Scratch folder, kept (default: a temporary one, removed)");
    app.add_option("--replay", options.replay, "Run the inputs kept in this folder again, one by one, instead");
    app.add_option("--batch", options.batch, "Inputs per ddtup process")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--jobs", options.jobs, "ddtup processes at once")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--timeout", options.timeout, "Seconds one input may take before it counts as a hang")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    RunSettings settings;
    settings.ddtup = fs::absolute(options.ddtup).string();
    settings.seconds_per_input = options.timeout;
    if (!fs::exists(settings.ddtup)) {
        std::fprintf(stderr, "fuzz: %s: no such executable\n", settings.ddtup.c_str());
        return 2;
    }
    try {
        if (!options.replay.empty()) return replay(options, settings);

        const auto start = std::chrono::steady_clock::now();
        clearFailures(options.out);
        WorkFolder work(options.work);
        std::vector<std::vector<Seed>> seeds;
        std::vector<std::pair<const Format*, Seed>> all_seeds;
        fs::create_directories(work / "seed-files");
        for (const Format& format : allFormats()) {
            seeds.push_back(makeSeeds(format.name, (work / "seed-files").string()));
            for (const Seed& seed : seeds.back()) all_seeds.push_back({&format, seed});
        }
        const int refused_seeds = checkSeeds(settings, all_seeds, work);
        const std::vector<Case> cases = makeCases(options, seeds, work);

        Fuzzer fuzzer(options, settings, work);
        for (const Format& format : allFormats())
            for (DamageKind kind : kDamageKinds) fuzzer.report().addRow(format.name, damageKindName(kind));
        fuzzer.run(cases);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

        std::printf("ddtup_fuzz --seed %llu --count %zu: %s\n", static_cast<unsigned long long>(options.seed),
                    options.count, settings.ddtup.c_str());
        fuzzer.report().print(stdout);
        std::printf("seed images: %zu, %d not accepted\n", all_seeds.size(), refused_seeds);
        if (fuzzer.strayLines()) std::printf("stderr lines that were not JSON events: %zu\n", fuzzer.strayLines());
        if (fuzzer.slowInputs())
            std::printf("inputs that ran out of time and were given %.0f s alone: %zu\n",
                        30 * options.timeout, fuzzer.slowInputs());
        if (fuzzer.tracerReruns())
            std::printf("runs made again after LeakSanitizer's tracer crashed at exit: %zu\n", fuzzer.tracerReruns());
        std::printf("time: %.1f s (%.0f inputs/s, %u jobs, %zu inputs per process)\n", seconds,
                    double(options.count) / seconds, options.jobs, options.batch);
        const int faults = fuzzer.report().faults() + refused_seeds;
        if (faults) std::printf("faults: %d; the inputs and their records are in %s\n", faults, options.out.c_str());
        return faults ? 1 : 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "fuzz: %s\n", error.what());
        return 2;
    }
}
