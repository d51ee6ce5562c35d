#include "allocation_watch.h"

#include <sys/resource.h>

#include <cstdlib>
#include <new>

#include "largest_size.h"

namespace ddt {

namespace {

constinit LargestSize host_blocks;

}  // namespace

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
std::optional<uint64_t> largestHostBlock() { return std::nullopt; }
#else
std::optional<uint64_t> largestHostBlock() { return host_blocks.largest(); }
#endif

uint64_t peakResidentBytes() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return uint64_t(usage.ru_maxrss) * 1024;  // Linux counts it in KiB
}

}  // namespace ddt

#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
namespace {

// As the standard's operator new: `allocate` again after each call of the new handler, until
// there is none.
template <class Allocate>
void* allocateOrThrow(Allocate allocate) {
    for (;;) {
        if (void* block = allocate()) return block;
        std::new_handler handler = std::get_new_handler();
        if (!handler) throw std::bad_alloc();
        handler();
    }
}

}  // namespace

// The replaceable allocation functions that take memory (the array and nothrow forms call
// these), with the blocks libstdc++'s take, so that its operator delete frees them (free).
void* operator new(std::size_t size) {
    ddt::host_blocks.note(size);
    return allocateOrThrow([&] { return std::malloc(size ? size : 1); });
}

void* operator new(std::size_t size, std::align_val_t alignment) {
    ddt::host_blocks.note(size);
    const std::size_t align = std::size_t(alignment);
    const std::size_t rounded = size ? (size + align - 1) / align * align : align;  // aligned_alloc's rule
    return allocateOrThrow([&] { return std::aligned_alloc(align, rounded); });
}
#endif
