#include "pipeline.h"

#include <atomic>
#include <new>
#include <thread>

#include "bounded_queue.h"

namespace ddt {

namespace {

// Runs one stage of a job; a failure is reported against the image and ends its way.
template <class Stage>
bool runStage(ImageJob& job, Reporter& reporter, Stage stage) {
    const std::string& input = job.task().input;
    try {
        stage();
        return true;
    } catch (const OutputClosed&) {
        // The other stage failed and said so.
    } catch (const UserError& error) {
        reporter.failed(input, error.what());
    } catch (const std::bad_alloc&) {
        reporter.failed(input, inputName(input) + ": out of memory");
    } catch (const std::exception& error) {
        reporter.failed(input, inputName(input) + ": internal error: " + error.what(), true);
    }
    return false;
}

}  // namespace

void runPipeline(const std::vector<ImageTask>& tasks, const Settings& settings,
                 const std::function<Backend*()>& backend, Reporter& reporter,
                 const std::function<void(const ImageJob&)>& on_done) {
    // One image waits between each pair of stages: at most four are in memory at once. The
    // writer takes an image as soon as it is being processed, and encodes its bands as they come.
    BoundedQueue<std::unique_ptr<ImageJob>> decoded(1);
    BoundedQueue<std::shared_ptr<ImageJob>> processed(1);
    std::atomic<bool> stopped = false;
    MemoryBudget budget(settings.memory ? settings.memory : defaultHostBudget());
    MemoryBudget bands(kBandBudgetBytes);

    std::thread reader([&] {
        for (size_t i = 0; i < tasks.size() && !stopped; ++i) {
            if (tasks[i].state != ImageTask::State::Ready || tasks[i].volume) continue;
            auto job = std::make_unique<ImageJob>(i, tasks[i], settings, reporter);
            if (!runStage(*job, reporter, [&] { job->open(); })) continue;
            job->holdMemory(budget.acquire(job->hostMemory()));
            if (runStage(*job, reporter, [&] { job->decode(); })) decoded.push(std::move(job));
        }
        decoded.close();
    });
    std::thread writer([&] {
        while (std::optional<std::shared_ptr<ImageJob>> job = processed.pop()) {
            bool written = false;
            if (runStage(**job, reporter, [&] { written = (*job)->write(); }) && written && on_done) on_done(**job);
        }
    });

    Backend* device = nullptr;
    while (std::optional<std::unique_ptr<ImageJob>> decoded_job = decoded.pop()) {
        if (!device && !stopped) device = backend();
        if (!device) {
            stopped = true;  // drop the decoded images: their temporary outputs go with them
            continue;
        }
        std::shared_ptr<ImageJob> job = std::move(*decoded_job);
        job->streamOutput(bands);
        processed.push(job);
        runStage(*job, reporter, [&] { job->process(*device); });
    }
    processed.close();
    reader.join();
    writer.join();
}

}  // namespace ddt
