// The pipeline's host-memory budget: a reader waits while images in flight fill it, and an
// image larger than the whole budget still runs once nothing else is held.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <optional>
#include <thread>

#include "memory_budget.h"

using ddt::MemoryBudget;

TEST_CASE("memory budget: an acquire waits until a lease ends") {
    MemoryBudget budget(100);
    std::optional<MemoryBudget::Lease> first = budget.acquire(60);
    std::atomic<bool> second_acquired = false;
    std::thread reader([&] {
        MemoryBudget::Lease second = budget.acquire(60);
        second_acquired = true;
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    CHECK(!second_acquired);  // 60 + 60 > 100
    first.reset();
    reader.join();
    CHECK(second_acquired);
}

TEST_CASE("memory budget: an image larger than the budget runs alone") {
    MemoryBudget budget(100);
    { MemoryBudget::Lease huge = budget.acquire(1000); }
    std::optional<MemoryBudget::Lease> small = budget.acquire(10);
    std::atomic<bool> huge_acquired = false;
    std::thread reader([&] {
        MemoryBudget::Lease huge = budget.acquire(1000);
        huge_acquired = true;
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    CHECK(!huge_acquired);  // waits for the small one
    small.reset();
    reader.join();
    CHECK(huge_acquired);
}
