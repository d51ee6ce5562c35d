// A small blocking queue between two pipeline stages. Its capacity bounds how many images
// wait between the stages, and so the memory a batch holds at once.
#pragma once

#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>

namespace ddt {

template <class T>
class BoundedQueue {
public:
    explicit BoundedQueue(size_t capacity) : capacity_(capacity) {}

    // Blocks while full.
    void push(T item) {
        std::unique_lock lock(mutex_);
        space_.wait(lock, [&] { return items_.size() < capacity_; });
        items_.push_back(std::move(item));
        ready_.notify_one();
    }
    // Blocks while empty; nothing once the queue is closed and drained.
    std::optional<T> pop() {
        std::unique_lock lock(mutex_);
        ready_.wait(lock, [&] { return !items_.empty() || closed_; });
        if (items_.empty()) return std::nullopt;
        T item = std::move(items_.front());
        items_.pop_front();
        space_.notify_one();
        return item;
    }
    // No more pushes; pop() drains what is left, then returns nothing.
    void close() {
        std::lock_guard lock(mutex_);
        closed_ = true;
        ready_.notify_all();
    }

private:
    size_t capacity_;
    std::mutex mutex_;
    std::condition_variable ready_, space_;
    std::deque<T> items_;
    bool closed_ = false;
};

}  // namespace ddt
