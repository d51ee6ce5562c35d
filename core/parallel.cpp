#include "parallel.h"

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <exception>
#include <fstream>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace ddt {

namespace {

// CPUs a quota of `quota` µs per `period` µs amounts to, rounded up; 0 for no quota.
unsigned quotaCpus(double quota, double period) {
    return quota > 0 && period > 0 ? unsigned(std::max(1.0, std::ceil(quota / period))) : 0;
}

// The tightest cpu.max ("QUOTA PERIOD" or "max PERIOD") from the process's cgroup v2 up to
// the root that is visible; 0 when none limits it.
unsigned cgroupV2Quota() {
    std::ifstream self("/proc/self/cgroup");
    std::string line, path;
    while (std::getline(self, line))
        if (line.rfind("0::", 0) == 0) path = line.substr(3);
    unsigned tightest = 0;
    for (std::string folder = "/sys/fs/cgroup" + path;; folder = folder.substr(0, folder.rfind('/'))) {
        std::ifstream max(folder + "/cpu.max");
        std::string quota;
        double period = 0;
        if (max >> quota >> period && quota != "max")
            if (unsigned cpus = quotaCpus(std::stod(quota), period); cpus && (!tightest || cpus < tightest))
                tightest = cpus;
        if (folder.size() <= std::string("/sys/fs/cgroup").size()) break;
    }
    return tightest;
}

// cgroup v1's CFS quota as a container sees it (-1: none).
unsigned cgroupV1Quota() {
    std::ifstream quota_file("/sys/fs/cgroup/cpu/cpu.cfs_quota_us"), period_file("/sys/fs/cgroup/cpu/cpu.cfs_period_us");
    double quota = -1, period = 0;
    return quota_file >> quota && period_file >> period ? quotaCpus(quota, period) : 0;
}

// One parallelFor: its chunks are claimed in order by whichever thread comes next.
struct Loop {
    const std::function<void(size_t, size_t)>* task = nullptr;
    size_t count = 0, chunk = 1, chunks = 0;
    std::atomic<size_t> next{0}, done{0};
    std::atomic<bool> failed{false};
    std::exception_ptr error;
    std::mutex mutex;
    std::condition_variable finished;

    bool exhausted() const { return next.load() >= chunks; }

    // Runs chunks until none is left to claim.
    void work() {
        for (size_t c; (c = next++) < chunks;) {
            if (!failed) {
                try {
                    (*task)(c * chunk, std::min(count, (c + 1) * chunk));
                } catch (...) {
                    std::lock_guard lock(mutex);
                    if (!error) error = std::current_exception();
                    failed = true;
                }
            }
            if (++done == chunks) {
                std::lock_guard lock(mutex);
                finished.notify_all();
            }
        }
    }
};

class Pool {
public:
    ~Pool() {
        {
            std::lock_guard lock(mutex_);
            stopping_ = true;
        }
        wake_.notify_all();
        for (std::thread& worker : workers_) worker.join();
    }

    void setThreads(unsigned count) { threads_ = count ? count : defaultThreadCount(); }
    unsigned threads() const { return threads_; }

    void run(size_t count, size_t grain, const std::function<void(size_t, size_t)>& task) {
        if (count == 0) return;
        const unsigned threads = threads_;
        // About four chunks a thread evens out uneven chunks without much claiming.
        const size_t chunk = std::max<size_t>({1, grain, (count + 4 * threads - 1) / (4 * threads)});
        if (threads == 1 || chunk >= count) {
            task(0, count);
            return;
        }
        auto loop = std::make_shared<Loop>();
        loop->task = &task;
        loop->count = count;
        loop->chunk = chunk;
        loop->chunks = (count + chunk - 1) / chunk;
        {
            std::lock_guard lock(mutex_);
            while (workers_.size() + 1 < threads) {
                const unsigned index = unsigned(workers_.size());
                workers_.emplace_back([this, index] { serve(index); });
            }
            loops_.push_back(loop);
        }
        wake_.notify_all();
        loop->work();
        {
            std::unique_lock lock(loop->mutex);
            loop->finished.wait(lock, [&] { return loop->done.load() == loop->chunks; });
        }
        if (loop->error) std::rethrow_exception(loop->error);
    }

private:
    // Worker `index` takes chunks of the oldest loop with chunks left, while it is among the
    // threads allowed.
    void serve(unsigned index) {
        std::unique_lock lock(mutex_);
        for (;;) {
            while (!loops_.empty() && loops_.front()->exhausted()) loops_.pop_front();
            if (stopping_) return;
            if (loops_.empty() || index + 1 >= threads_) {
                wake_.wait(lock);
                continue;
            }
            std::shared_ptr<Loop> loop = loops_.front();
            lock.unlock();
            loop->work();
            lock.lock();
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<std::shared_ptr<Loop>> loops_;
    std::vector<std::thread> workers_;
    bool stopping_ = false;
    std::atomic<unsigned> threads_{defaultThreadCount()};
};

Pool& pool() {
    static Pool instance;
    return instance;
}

}  // namespace

unsigned defaultThreadCount() {
    cpu_set_t set;
    CPU_ZERO(&set);
    unsigned cpus = sched_getaffinity(0, sizeof set, &set) == 0 ? unsigned(CPU_COUNT(&set)) : 0;
    if (cpus == 0) cpus = std::max(1u, std::thread::hardware_concurrency());
    for (unsigned quota : {cgroupV2Quota(), cgroupV1Quota()})
        if (quota) cpus = std::min(cpus, quota);
    return std::max(1u, cpus);
}

void setThreadCount(unsigned count) { pool().setThreads(count); }

unsigned threadCount() { return pool().threads(); }

void parallelFor(size_t count, size_t grain, const std::function<void(size_t, size_t)>& task) {
    pool().run(count, grain, task);
}

}  // namespace ddt
