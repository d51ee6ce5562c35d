// The backends a tiled job's tiles run on at once (app/tiled_upscale.h,
// app/simplified_upscale.h): where the backend has twins (the CPU), one per thread.
#pragma once

#include <algorithm>
#include <memory>
#include <mutex>
#include <vector>

#include "backend.h"
#include "parallel.h"

namespace ddt {

// Tiles processed at once: one per thread where the backend has twins (the CPU), else one.
inline uint32_t tilesAtOnce(const Backend& backend) { return backend.twin() ? std::max(1u, threadCount()) : 1; }

// The backends a strip's tiles run on: the caller's, and where it has twins, one more per
// thread, so that tiles are processed in parallel. A tile borrows one for its whole way.
class BackendPool {
public:
    BackendPool(Backend& backend, uint32_t size) : hand_over_surfaces_(backend.handsOverSurface()) {
        free_.push_back(&backend);
        for (uint32_t i = 1; i < size; ++i) {
            twins_.push_back(backend.twin());
            free_.push_back(twins_.back().get());
        }
    }
    uint32_t size() const { return uint32_t(twins_.size() + 1); }
    bool handOverSurfaces() const { return hand_over_surfaces_; }

    template <typename Task>
    auto withBackend(Task task) {
        Backend* backend;
        {
            std::lock_guard lock(mutex_);
            backend = free_.back();  // never empty: at most size() tasks run at once
            free_.pop_back();
        }
        struct Return {
            BackendPool& pool;
            Backend* backend;
            ~Return() {
                std::lock_guard lock(pool.mutex_);
                pool.free_.push_back(backend);
            }
        } give_back{*this, backend};
        return task(*backend);
    }

private:
    bool hand_over_surfaces_;
    std::mutex mutex_;
    std::vector<std::unique_ptr<Backend>> twins_;
    std::vector<Backend*> free_;
};

}  // namespace ddt
