// The shared thread pool (core/parallel.h): every item once, exceptions carried to the caller,
// loops from several threads and from inside a loop, and the thread count it is given.
#include <catch2/catch.hpp>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include "parallel.h"

namespace {

// Restores the thread count a test changed.
struct ScopedThreadCount {
    explicit ScopedThreadCount(unsigned count) : before(ddt::threadCount()) { ddt::setThreadCount(count); }
    ~ScopedThreadCount() { ddt::setThreadCount(before); }
    unsigned before;
};

// Runs a loop over `count` items and counts how often each was visited; one more count at the
// end holds the chunks that were empty or ran past the last item. The workers only count:
// Catch2's assertions are not thread-safe (ThreadSanitizer reports them from the pool).
std::vector<int> visits(size_t count, size_t grain) {
    std::vector<std::atomic<int>> seen(count + 1);
    ddt::parallelFor(count, grain, [&](size_t begin, size_t end) {
        if (begin >= end || end > count) {
            ++seen[count];
            return;
        }
        for (size_t i = begin; i < end; ++i) ++seen[i];
    });
    return std::vector<int>(seen.begin(), seen.end());
}

// What visits() gives when each item is visited once by a sound chunk.
std::vector<int> onceEach(size_t count) {
    std::vector<int> expected(count, 1);
    expected.push_back(0);
    return expected;
}

}  // namespace

TEST_CASE("parallel: every item is visited exactly once, whatever the count, grain and threads", "[threads]") {
    for (unsigned threads : {1u, 2u, 5u}) {
        ScopedThreadCount scoped(threads);
        for (size_t count : {size_t(0), size_t(1), size_t(7), size_t(1000), size_t(100003)})
            for (size_t grain : {size_t(1), size_t(8), size_t(5000)}) {
                INFO(threads << " threads, " << count << " items, grain " << grain);
                CHECK(visits(count, grain) == onceEach(count));
            }
    }
}

TEST_CASE("parallel: a chunk's exception reaches the caller, and the pool keeps working", "[threads]") {
    ScopedThreadCount scoped(3);
    CHECK_THROWS_WITH(ddt::parallelFor(1000, 1,
                                       [](size_t begin, size_t end) {
                                           if (begin <= 500 && 500 < end) throw std::runtime_error("item 500");
                                       }),
                      "item 500");
    CHECK(visits(1000, 1) == onceEach(1000));
}

TEST_CASE("parallel: loops from several threads and loops inside loops all finish", "[threads]") {
    ScopedThreadCount scoped(2);
    std::atomic<size_t> total = 0;
    auto nested = [&] {
        ddt::parallelFor(16, 1, [&](size_t begin, size_t end) {
            for (size_t i = begin; i < end; ++i)
                ddt::parallelFor(100, 1, [&](size_t b, size_t e) { total += e - b; });
        });
    };
    std::vector<std::thread> callers;
    for (int i = 0; i < 3; ++i) callers.emplace_back(nested);
    for (std::thread& caller : callers) caller.join();
    CHECK(total == 3 * 16 * 100);
}

TEST_CASE("parallel: the thread count is what was set, and 0 means the default", "[threads]") {
    ScopedThreadCount scoped(3);
    CHECK(ddt::threadCount() == 3);
    ddt::setThreadCount(0);
    CHECK(ddt::threadCount() == ddt::defaultThreadCount());
    CHECK(ddt::defaultThreadCount() >= 1);
    CHECK(ddt::defaultThreadCount() <= std::max(1u, std::thread::hardware_concurrency()));
}
