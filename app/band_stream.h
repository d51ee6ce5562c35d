// The rendered rows of one image on their way from the process stage to the write stage, so
// that rendering and encoding overlap and no image's output is ever held whole. Bands in
// flight, over all images of a run, stay within one MemoryBudget: a renderer that gets ahead
// of its encoder waits. Either side can give up: the other then stops without a word (the
// side that failed reports the image).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>

#include "memory_budget.h"
#include "output_rows.h"

namespace ddt {

// Thrown to the renderer when the encoder gave up on the image (its failure is reported).
struct OutputClosed : std::exception {
    const char* what() const noexcept override { return "the output was closed"; }
};

struct Band {
    OutputRows rows;
    MemoryBudget::Lease lease;  // the band's bytes in the run's budget
};

class BandStream {
public:
    explicit BandStream(MemoryBudget& budget) : budget_(budget) {}

    // Renderer: sends `rows` of `bytes` bytes in all; waits while the budget is spent. Throws
    // OutputClosed once the encoder has given up.
    void send(OutputRows&& rows, size_t bytes) {
        if (refused()) throw OutputClosed();
        Band band{std::move(rows), budget_.acquire(bytes)};
        std::lock_guard lock(mutex_);
        if (refused_) throw OutputClosed();
        bands_.push_back(std::move(band));
        changed_.notify_all();
    }
    // Renderer: every row was sent.
    void finish() { end(true); }
    // Renderer: the image failed; the encoder drops what it has.
    void abandon() { end(false); }

    // Encoder: the next band, or nothing at the end of the stream; complete() then says
    // whether every row came.
    std::optional<Band> receive() {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return !bands_.empty() || ended_; });
        if (bands_.empty()) return std::nullopt;
        Band band = std::move(bands_.front());
        bands_.pop_front();
        return band;
    }
    bool complete() {
        std::lock_guard lock(mutex_);
        return ended_ && complete_;
    }
    // Encoder: writing failed; the renderer stops at its next band.
    void refuse() {
        std::lock_guard lock(mutex_);
        refused_ = true;
        bands_.clear();
    }

private:
    bool refused() {
        std::lock_guard lock(mutex_);
        return refused_;
    }
    void end(bool complete) {
        std::lock_guard lock(mutex_);
        ended_ = true;
        complete_ = complete;
        changed_.notify_all();
    }

    MemoryBudget& budget_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<Band> bands_;
    bool ended_ = false, complete_ = false, refused_ = false;
};

}  // namespace ddt
