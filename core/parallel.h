// The process's worker threads, shared by every parallel step (the reconstruction's passes,
// rendering bands, optimizing tiles, PNG deflate chunks), so that their sum never exceeds
// what --threads allows. OpenImageIO keeps its own pool for decoding; app/ sizes it alike.
#pragma once

#include <cstddef>
#include <functional>

namespace ddt {

// The processors this process may use: its CPU affinity, capped by a cgroup CPU quota
// (cgroup v2 cpu.max or v1 cfs_quota_us, rounded up), at least 1.
unsigned defaultThreadCount();

// Sets the number of threads a parallelFor uses, the calling thread included (0: the default).
// Call before the first parallelFor; later calls take effect for later loops.
void setThreadCount(unsigned count);
unsigned threadCount();

// Runs task(begin, end) over [0, count) in chunks of at least `grain` items, on the caller and
// the pool's workers; returns when every chunk is done. The first exception a chunk throws
// is rethrown here (the chunks not yet started are skipped). May be called from several
// threads at once and from inside a task: a caller works on its own loop while it waits.
void parallelFor(size_t count, size_t grain, const std::function<void(size_t begin, size_t end)>& task);

}  // namespace ddt
