// Progress as text on stderr: one line per error or note, and on a terminal a live line that
// is redrawn in place ("[3/50] photo.png: optimize · 0:12 elapsed · ~0:40 left").
#include <sys/ioctl.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "checked_file.h"
#include "reporter.h"

namespace ddt {

namespace {

std::string clock(double seconds) {
    const long total = std::lround(seconds);
    char text[32];
    if (total >= 3600)
        std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", total / 3600, total / 60 % 60, total % 60);
    else
        std::snprintf(text, sizeof text, "%ld:%02ld", total / 60, total % 60);
    return text;
}

// The terminal's width in columns, or 0 when unknown.
size_t terminalColumns(int fd) {
    winsize size{};
    return ::ioctl(fd, TIOCGWINSZ, &size) == 0 ? size.ws_col : 0;
}

// The longest prefix of `text` that fits `columns` (one column per UTF-8 character), so the
// live line never wraps: a wrapped line could not be redrawn in place.
std::string fitted(const std::string& text, size_t columns) {
    if (columns == 0) return text;
    size_t characters = 0;
    for (size_t i = 0; i < text.size(); ++i) {
        if ((static_cast<unsigned char>(text[i]) & 0xC0) == 0x80) continue;  // continuation byte
        if (++characters == columns) return text.substr(0, i);
    }
    return text;
}

class TextProgress final : public ProgressSink {
public:
    TextProgress(int fd, Verbosity verbosity, bool live) : fd_(fd), verbosity_(verbosity), live_(live) {}

    ~TextProgress() override { clearLive(); }

    void start(size_t images) override { batch_ = images > 1; }

    void backend(const BackendChoice& choice) override {
        if (verbosity_ == Verbosity::Quiet) return;
        const std::string what = choice.backend == "cpu"
                                     ? "the CPU backend (" + std::to_string(choice.threads) + (choice.threads == 1 ? " thread)" : " threads)")
                                     : choice.device_name + " (" + choice.device_type + ")";
        // --backend auto always says what it picked: a user who expected a GPU learns why not.
        if (!choice.reason.empty()) line("note: using " + what + ": " + choice.reason);
        else if (choice.device_type == "cpu")
            // Users of other Vulkan upscalers were silently given a software device and thought it hung.
            line("note: running on " + choice.device_name + ", a CPU Vulkan device; expect it to be slower than a GPU");
        else if (verbosity_ == Verbosity::Verbose)
            line("using " + what);
    }

    void stage(const RunCounts& counts, size_t index, const std::string& input, Stage stage, uint32_t tile,
               uint32_t tiles) override {
        if (!live_) return;
        std::string status = "[";
        status.append(std::to_string(index + 1)).append("/").append(std::to_string(counts.total)).append("] ");
        status.append(input).append(": ").append(stageName(stage));
        if (tiles > 1) status.append(" (tile ").append(std::to_string(tile + 1)).append("/").append(std::to_string(tiles)).append(")");
        status.append(" · ").append(clock(counts.elapsed_s)).append(" elapsed");
        if (counts.remaining_s >= 0.0) status.append(" · ~").append(clock(counts.remaining_s)).append(" left");
        live_text_ = status;
        drawLive();
    }

    void done(const RunCounts&, size_t, const ImageTask& task, OutputSize size, double seconds) override {
        if (verbosity_ != Verbosity::Verbose) return;
        char detail[96];
        if (size.depth)
            std::snprintf(detail, sizeof detail, " (%u×%u×%u, %.2f s)", size.width, size.height, size.depth, seconds);
        else
            std::snprintf(detail, sizeof detail, " (%u×%u, %.2f s)", size.width, size.height, seconds);
        line(task.input + " -> " + task.output + detail);
    }

    void skipped(const RunCounts&, size_t, const ImageTask& task) override {
        if (verbosity_ == Verbosity::Verbose) line(task.input + ": skipped, " + task.output + " exists");
    }

    void notice(const std::string&, const std::string& message) override {
        if (verbosity_ != Verbosity::Quiet) line("note: " + message);
    }

    void error(const std::string&, const std::string& message) override { line(message); }

    void failed(const RunCounts&, const std::string&, const std::string& message) override { line(message); }

    void summary(const RunCounts& counts, const std::vector<std::string>& failures, int) override {
        clearLive();
        if (!batch_ || (verbosity_ == Verbosity::Quiet && failures.empty())) return;
        line("summary: " + std::to_string(counts.done) + " done, " + std::to_string(counts.skipped) + " skipped, " +
             std::to_string(counts.failed) + " failed in " + clock(counts.elapsed_s));
        for (const std::string& failure : failures) line("failed: " + failure);
    }

private:
    // A failure means stderr is gone: there is no one left to tell.
    void write(const std::string& text) { writeAll(fd_, text.data(), text.size()); }
    // A message on its own line, with the live line redrawn under it.
    void line(const std::string& message) {
        clearLive();
        write("ddtup: " + message + "\n");
        drawLive();
    }
    void drawLive() {
        if (!live_ || live_text_.empty()) return;
        write("\r\033[K" + fitted(live_text_, terminalColumns(fd_)));
        live_shown_ = true;
    }
    void clearLive() {
        if (!live_shown_) return;
        write("\r\033[K");
        live_shown_ = false;
    }

    int fd_;
    Verbosity verbosity_;
    bool live_;
    bool batch_ = false;
    bool live_shown_ = false;
    std::string live_text_;
};

}  // namespace

std::unique_ptr<ProgressSink> makeTextProgress(int fd, Verbosity verbosity, bool live_line) {
    return std::make_unique<TextProgress>(fd, verbosity, live_line);
}

}  // namespace ddt
