// What --stats says about the process's memory: its peak resident size and the largest single
// block it asked for with `new` (which ddtup's own operator new notes, allocation_watch.cpp).
#pragma once

#include <cstdint>
#include <optional>

namespace ddt {

// The largest block allocated by `new` so far; none in sanitized builds, whose runtimes
// replace operator new with their own.
std::optional<uint64_t> largestHostBlock();

// The process's peak resident set so far, in bytes (getrusage).
uint64_t peakResidentBytes();

}  // namespace ddt
