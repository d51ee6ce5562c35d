// The pipeline's host-memory budget: a reader waits while images in flight fill it, and an
// image larger than the whole budget still runs once nothing else is held.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <optional>
#include <thread>

#include "memory_budget.h"

using ddt::MemoryBudget;

namespace {

// Whether acquiring `bytes` waits while `held` lasts and succeeds once it ends. Within 100 ms
// a reader that is let through has long taken its lease, so a budget that fails to wait is
// caught; a budget that waits passes however slow the machine.
bool waitsFor(MemoryBudget& budget, std::optional<MemoryBudget::Lease>& held, uint64_t bytes) {
    std::atomic<bool> acquired = false;
    std::thread reader([&] {
        MemoryBudget::Lease lease = budget.acquire(bytes);
        acquired = true;
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const bool waited = !acquired;
    held.reset();
    reader.join();
    return waited && acquired;
}

}  // namespace

TEST_CASE("memory budget: an acquire waits until a lease ends", "[threads]") {
    MemoryBudget budget(100);
    std::optional<MemoryBudget::Lease> first = budget.acquire(60);
    CHECK(waitsFor(budget, first, 60));  // 60 + 60 > 100
}

TEST_CASE("memory budget: an image larger than the budget runs alone", "[threads]") {
    MemoryBudget budget(100);
    { MemoryBudget::Lease huge = budget.acquire(1000); }  // alone: it does not wait
    std::optional<MemoryBudget::Lease> small = budget.acquire(10);
    CHECK(waitsFor(budget, small, 1000));  // not beside the small one
}
