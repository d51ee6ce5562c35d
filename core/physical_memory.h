// How much memory the machine has, for budgets and for the CPU backend's tile sizes.
#pragma once

#include <unistd.h>

#include <cstdint>

namespace ddt {

// The machine's physical memory in bytes (4 GiB when the system does not say).
inline uint64_t physicalMemory() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page_size > 0 ? uint64_t(pages) * uint64_t(page_size) : uint64_t(4) << 30;
}

}  // namespace ddt
