#include "reporter.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>

#include "checked_file.h"
#include "exit_codes.h"

namespace ddt {

const char* stageName(Stage stage) {
    switch (stage) {
        case Stage::Read:
            return "read";
        case Stage::Optimize:
            return "optimize";
        case Stage::Render:
            return "render";
        case Stage::Write:
            return "write";
    }
    return "?";
}

Reporter::Reporter(const Settings& settings) {
    fd_ = ::fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 0);
    if (fd_ < 0) fd_ = STDERR_FILENO;
    if (settings.progress == ProgressMode::Json) {
        sink_ = makeJsonProgress(fd_);
    } else {
        const bool live = settings.progress == ProgressMode::Bar ||
                          (settings.progress == ProgressMode::Auto && ::isatty(STDERR_FILENO) && !settings.quiet());
        sink_ = makeTextProgress(fd_, settings.verbosity, live);
        if (live) ticker_ = std::thread([this] { tickWhileRunning(); });
    }
}

Reporter::~Reporter() {
    {
        std::lock_guard lock(mutex_);
        finished_ = true;
    }
    finished_signal_.notify_all();
    if (ticker_.joinable()) ticker_.join();
    sink_.reset();
    if (fd_ != STDERR_FILENO) ::close(fd_);
}

double remainingSeconds(const RunCounts& counts, const std::optional<TiledImageProgress>& tiled) {
    // Skipped images take no time; the rest are assumed to take the average so far.
    const size_t finished = counts.done + counts.failed;
    const size_t left = counts.total - finished - counts.skipped;
    const double average = finished ? counts.elapsed_s / double(finished) : -1.0;
    if (!tiled || tiled->tiles_done == 0 || left == 0) return average < 0.0 ? -1.0 : average * double(left);
    const double per_tile = tiled->seconds / tiled->tiles_done;
    const double current_left = per_tile * std::max(0.0, double(tiled->tiles) - tiled->tiles_done);
    const double per_image = average >= 0.0 ? average : per_tile * tiled->tiles;
    return current_left + per_image * double(left - 1);
}

RunCounts Reporter::countsLocked() const {
    RunCounts counts = counts_;
    const auto now = std::chrono::steady_clock::now();
    counts.elapsed_s = std::chrono::duration<double>(now - start_).count();
    std::optional<TiledImageProgress> tiled;
    if (tiled_) tiled = TiledImageProgress{std::chrono::duration<double>(now - tiled_->since).count(), tiled_->tile, tiled_->tiles};
    counts.remaining_s = remainingSeconds(counts, tiled);
    return counts;
}

void Reporter::start(size_t images) {
    std::lock_guard lock(mutex_);
    counts_.total = images;
    sink_->start(images);
}

void Reporter::backend(const BackendChoice& choice) {
    std::lock_guard lock(mutex_);
    sink_->backend(choice);
}

void Reporter::stage(size_t index, const std::string& input, Stage stage, uint32_t tile, uint32_t tiles) {
    std::lock_guard lock(mutex_);
    last_stage_ = LastStage{index, input, stage, tile, tiles};
    // Tiles are counted from the first tile's optimisation. The next image's read, on another
    // thread, leaves the count alone; the write comes after the last tile.
    if (stage == Stage::Optimize || stage == Stage::Render) {
        if (tiles <= 1)
            tiled_.reset();
        else if (!tiled_ || tiled_->index != index)
            tiled_ = TiledImage{index, input, std::chrono::steady_clock::now(), tile, tiles};
        else
            tiled_->tile = tile, tiled_->tiles = tiles;
    } else if (stage == Stage::Write && tiled_ && tiled_->index == index) {
        tiled_->tile = tiled_->tiles;  // every tile is done
    }
    sink_->stage(countsLocked(), index, input, stage, tile, tiles);
}

void Reporter::tickWhileRunning() {
    std::unique_lock lock(mutex_);
    while (!finished_signal_.wait_for(lock, std::chrono::seconds(1), [&] { return finished_; }))
        if (last_stage_)
            sink_->stage(countsLocked(), last_stage_->index, last_stage_->input, last_stage_->stage, last_stage_->tile,
                         last_stage_->tiles);
}

void Reporter::done(size_t index, const ImageTask& task, OutputSize size, double seconds) {
    std::lock_guard lock(mutex_);
    ++counts_.done;
    if (tiled_ && tiled_->index == index) tiled_.reset();
    sink_->done(countsLocked(), index, task, size, seconds);
}

void Reporter::skipped(size_t index, const ImageTask& task) {
    std::lock_guard lock(mutex_);
    ++counts_.skipped;
    sink_->skipped(countsLocked(), index, task);
}

void Reporter::notice(const std::string& input, const std::string& message) {
    std::lock_guard lock(mutex_);
    sink_->notice(input, message);
}

void Reporter::failed(const std::string& input, const std::string& message, bool internal) {
    std::lock_guard lock(mutex_);
    ++counts_.failed;
    if (tiled_ && tiled_->input == input) tiled_.reset();
    internal_error_ |= internal;
    failures_.push_back(message);
    sink_->failed(countsLocked(), input, message);
}

void Reporter::fatal(const std::string& message, int exit_code) {
    std::lock_guard lock(mutex_);
    fatal_exit_code_ = exit_code;
    sink_->error("", message);
}

int Reporter::finish() {
    std::lock_guard lock(mutex_);
    finished_ = true;
    finished_signal_.notify_all();
    const int exit_code = fatal_exit_code_   ? fatal_exit_code_
                          : internal_error_  ? int(kExitInternal)
                          : counts_.failed   ? int(kExitSomeFailed)
                                             : int(kExitDone);
    sink_->summary(countsLocked(), failures_, exit_code);
    return exit_code;
}

}  // namespace ddt
