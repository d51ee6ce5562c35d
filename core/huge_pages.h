// Large arrays on 2 MiB pages (Linux transparent huge pages): a gigapixel-class reconstruction
// touches about a kilobyte per input pixel, and on 4 KiB pages its first writes cost a page
// fault per 4 KiB and its passes a TLB miss on nearly every scattered access.
#pragma once

#include <cstddef>
#include <vector>

namespace ddt {

// Asks the kernel to back [data, data + bytes) with huge pages where it can; a hint that
// changes nothing else (and nothing at all on other systems). For memory not yet written.
void adviseHugePages(const void* data, size_t bytes);

// v.reserve(count), the new storage advised for huge pages before anything writes it.
template <typename T>
void reserveOnHugePages(std::vector<T>& v, size_t count) {
    if (count <= v.capacity()) return;
    v.reserve(count);
    adviseHugePages(v.data(), count * sizeof(T));
}

// A vector of `count` copies of `value` on huge pages.
template <typename T>
std::vector<T> vectorOnHugePages(size_t count, const T& value = T()) {
    std::vector<T> v;
    reserveOnHugePages(v, count);
    v.assign(count, value);
    return v;
}

}  // namespace ddt
