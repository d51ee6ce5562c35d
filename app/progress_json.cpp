// Progress as one JSON object per line on stderr (--progress=json), for scripts and GUIs.
// Errors and notes are events too, so a reader never has to parse free text. The events and
// their fields are listed in docs/USAGE.md ("Progress") and the man page.
#include <unistd.h>

#include "checked_file.h"
#include "json_line.h"
#include "reporter.h"

namespace ddt {

namespace {

class JsonProgress final : public ProgressSink {
public:
    explicit JsonProgress(int fd) : fd_(fd) {}

    void start(size_t images) override { emit(JsonLine().field("event", "start").field("images", uint64_t(images))); }

    void backend(const BackendChoice& choice) override {
        JsonLine event;
        event.field("event", "device").field("backend", choice.backend);
        if (choice.backend == "vulkan") event.field("name", choice.device_name).field("type", choice.device_type);
        else event.field("threads", uint64_t(choice.threads));
        if (!choice.reason.empty()) event.field("reason", choice.reason);
        emit(event);
    }

    void stage(const RunCounts& counts, size_t index, const std::string& input, Stage stage, uint32_t tile,
               uint32_t tiles) override {
        JsonLine event;
        event.field("event", "stage").field("index", uint64_t(index)).field("input", input).field("stage", stageName(stage));
        if (tiles > 1) event.field("tile", uint64_t(tile)).field("tiles", uint64_t(tiles));
        emit(event.field("elapsed", counts.elapsed_s).field("remaining", counts.remaining_s));
    }

    void done(const RunCounts& counts, size_t index, const ImageTask& task, OutputSize size, double seconds) override {
        JsonLine event;
        event.field("event", "done")
            .field("index", uint64_t(index))
            .field("input", task.input)
            .field("output", task.output)
            .field("width", uint64_t(size.width))
            .field("height", uint64_t(size.height));
        if (size.depth) event.field("depth", uint64_t(size.depth));  // volumes only
        emit(event.field("seconds", seconds));
        progress(counts);
    }

    void skipped(const RunCounts& counts, size_t index, const ImageTask& task) override {
        emit(JsonLine()
                 .field("event", "skipped")
                 .field("index", uint64_t(index))
                 .field("input", task.input)
                 .field("output", task.output)
                 .field("reason", task.reason));
        progress(counts);
    }

    void notice(const std::string& input, const std::string& message) override {
        JsonLine event;
        event.field("event", "notice");
        if (!input.empty()) event.field("input", input);
        emit(event.field("message", message));
    }

    void error(const std::string& input, const std::string& message) override {
        JsonLine event;
        event.field("event", "error");
        if (!input.empty()) event.field("input", input);
        emit(event.field("message", message));
    }

    void failed(const RunCounts& counts, const std::string& input, const std::string& message) override {
        error(input, message);
        progress(counts);
    }

    void summary(const RunCounts& counts, const std::vector<std::string>&, int exit_code) override {
        emit(JsonLine()
                 .field("event", "summary")
                 .field("done", uint64_t(counts.done))
                 .field("skipped", uint64_t(counts.skipped))
                 .field("failed", uint64_t(counts.failed))
                 .field("seconds", counts.elapsed_s)
                 .field("exit_code", exit_code));
    }

private:
    void progress(const RunCounts& counts) {
        emit(JsonLine()
                 .field("event", "progress")
                 .field("done", uint64_t(counts.done))
                 .field("skipped", uint64_t(counts.skipped))
                 .field("failed", uint64_t(counts.failed))
                 .field("total", uint64_t(counts.total))
                 .field("elapsed", counts.elapsed_s)
                 .field("remaining", counts.remaining_s));
    }
    void emit(const JsonLine& event) {
        const std::string text = event.text();
        writeAll(fd_, text.data(), text.size());  // a failure means stderr is gone
    }

    int fd_;
};

}  // namespace

std::unique_ptr<ProgressSink> makeJsonProgress(int fd) { return std::make_unique<JsonProgress>(fd); }

}  // namespace ddt
