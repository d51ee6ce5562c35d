// Host memory the pipeline's images may hold at once. Reading ahead is worth it for small
// images, but three 16384² images in flight would not fit a machine: the reader waits for
// room before decoding. An image larger than the whole budget still runs, alone.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <mutex>

#include "physical_memory.h"

namespace ddt {

class MemoryBudget {
public:
    explicit MemoryBudget(uint64_t bytes) : limit_(bytes) {}

    // What an image holds until its lease ends: given back when the lease is destroyed.
    class Lease {
    public:
        Lease() = default;
        Lease(MemoryBudget* budget, uint64_t bytes) : budget_(budget), bytes_(bytes) {}
        Lease(Lease&& other) noexcept : budget_(other.budget_), bytes_(other.bytes_) { other.budget_ = nullptr; }
        Lease& operator=(Lease&& other) noexcept {
            std::swap(budget_, other.budget_);
            std::swap(bytes_, other.bytes_);
            return *this;
        }
        ~Lease() {
            if (budget_) budget_->release(bytes_);
        }

    private:
        MemoryBudget* budget_ = nullptr;
        uint64_t bytes_ = 0;
    };

    // Blocks until `bytes` fit beside what is held, or nothing is held.
    Lease acquire(uint64_t bytes) {
        std::unique_lock lock(mutex_);
        room_.wait(lock, [&] { return held_ == 0 || held_ + bytes <= limit_; });
        held_ += bytes;
        return Lease(this, bytes);
    }

private:
    void release(uint64_t bytes) {
        std::lock_guard lock(mutex_);
        held_ -= bytes;
        room_.notify_all();
    }

    std::mutex mutex_;
    std::condition_variable room_;
    uint64_t limit_;
    uint64_t held_ = 0;
};

// What the pipeline's images may hold: half the physical memory; the rest is for the device
// (lavapipe's buffers live in host memory too) and everything else.
inline uint64_t defaultHostBudget() { return physicalMemory() / 2; }

}  // namespace ddt
