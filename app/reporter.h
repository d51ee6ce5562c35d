// What a run tells its user: errors, notes, progress and the closing summary, as text (with a
// live progress line on a terminal) or as one JSON event per line (--progress=json). Safe to
// call from the pipeline's threads. It also keeps the counts that decide the exit code.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "batch_plan.h"
#include "render.h"
#include "settings.h"

namespace ddt {

enum class Stage { Read, Optimize, Render, Write };

// Which backend a run uses, told once per run: the Vulkan device, or the CPU backend and its
// threads; `reason` says why --backend auto chose it ("" when the user named the backend).
struct BackendChoice {
    std::string backend;      // "vulkan" or "cpu"
    std::string device_name;  // Vulkan: the device
    std::string device_type;  // Vulkan: "discrete", "integrated", "virtual", "cpu" or "other"
    unsigned threads = 0;     // CPU: worker threads
    std::string reason;
};
const char* stageName(Stage stage);

struct RunCounts {
    size_t total = 0;
    size_t done = 0;
    size_t skipped = 0;
    size_t failed = 0;
    double elapsed_s = 0.0;
    double remaining_s = -1.0;  // < 0: not known yet
};

// How far the image being processed in tiles is: `tiles_done` of `tiles` after `seconds`.
struct TiledImageProgress {
    double seconds = 0.0;
    uint32_t tiles_done = 0;
    uint32_t tiles = 0;
};

// The time the run still needs, or -1 when there is nothing yet to go by: the average of the
// finished images for each image left, and for an image in tiles, its own pace over the
// tiles it has done (a single large image would otherwise show no estimate until the end).
double remainingSeconds(const RunCounts& counts, const std::optional<TiledImageProgress>& tiled);

// Where the events go; text and JSON implement it (progress_text.cpp, progress_json.cpp).
class ProgressSink {
public:
    virtual ~ProgressSink() = default;
    virtual void start(size_t images) = 0;
    virtual void backend(const BackendChoice& choice) = 0;
    virtual void stage(const RunCounts& counts, size_t index, const std::string& input, Stage stage, uint32_t tile,
                       uint32_t tiles) = 0;
    virtual void done(const RunCounts& counts, size_t index, const ImageTask& task, OutputSize size, double seconds) = 0;
    virtual void skipped(const RunCounts& counts, size_t index, const ImageTask& task) = 0;
    virtual void notice(const std::string& input, const std::string& message) = 0;
    virtual void error(const std::string& input, const std::string& message) = 0;
    // An image failed: its error, and the counts that include it.
    virtual void failed(const RunCounts& counts, const std::string& input, const std::string& message) = 0;
    // `failures` holds each failed image's message.
    virtual void summary(const RunCounts& counts, const std::vector<std::string>& failures, int exit_code) = 0;
};

// Writes to a duplicate of the standard error taken at start, so that a codec silencing
// stderr for a moment (core/image.cpp) cannot swallow a message from another thread.
std::unique_ptr<ProgressSink> makeTextProgress(int fd, Verbosity verbosity, bool live_line);
std::unique_ptr<ProgressSink> makeJsonProgress(int fd);

class Reporter {
public:
    explicit Reporter(const Settings& settings);
    ~Reporter();
    Reporter(const Reporter&) = delete;
    Reporter& operator=(const Reporter&) = delete;

    void start(size_t images);
    void backend(const BackendChoice& choice);
    void stage(size_t index, const std::string& input, Stage stage, uint32_t tile = 0, uint32_t tiles = 0);
    void done(size_t index, const ImageTask& task, OutputSize size, double seconds);
    void skipped(size_t index, const ImageTask& task);
    void notice(const std::string& input, const std::string& message);  // `message` names its file
    // An image failed; `internal` when by a bug in ddtup rather than its input (exit code 4).
    void failed(const std::string& input, const std::string& message, bool internal = false);
    // An error that ends the run before or outside any image (usage, no device, a bug).
    void fatal(const std::string& message, int exit_code);
    // Prints the summary; returns the exit code the counts call for.
    int finish();

private:
    struct LastStage {
        size_t index = 0;
        std::string input;
        Stage stage = Stage::Read;
        uint32_t tile = 0, tiles = 0;
    };
    struct TiledImage {
        size_t index = 0;
        std::string input;
        std::chrono::steady_clock::time_point since;
        uint32_t tile = 0, tiles = 0;
    };
    RunCounts countsLocked() const;
    // Redraws the live line every second, so that its clock runs during a long stage.
    void tickWhileRunning();

    std::mutex mutex_;
    int fd_ = -1;
    std::unique_ptr<ProgressSink> sink_;
    RunCounts counts_;
    std::vector<std::string> failures_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    int fatal_exit_code_ = 0;
    bool internal_error_ = false;
    std::optional<LastStage> last_stage_;
    std::optional<TiledImage> tiled_;  // the image being optimised or rendered, when in tiles
    bool finished_ = false;
    std::condition_variable finished_signal_;
    std::thread ticker_;
};

}  // namespace ddt
