// Measuring a triangulation in a forked child process, so that each library's peak memory is
// its own: the child resets its peak resident set (VmHWM, by writing 5 to
// /proc/self/clear_refs) just before the measured span and reads it just after; the peak
// memory reported is VmHWM at the end minus VmRSS at the reset. The input, inherited from the
// parent or converted before the span, is resident at the reset and so not counted.
// The child sends its results back through a pipe; one that runs past a time limit is killed.
#pragma once

#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

namespace bench {

// Bytes the child sends back: plain values, strings, arrays of uint64_t, read in the order
// they were written.
class Payload {
public:
    template <typename T>
    void put(const T& value) {
        const char* p = reinterpret_cast<const char*>(&value);
        bytes_.insert(bytes_.end(), p, p + sizeof(T));
    }
    void putString(const std::string& text);
    void putArray(const std::vector<uint64_t>& values);

    template <typename T>
    T get() {
        T value;
        std::memcpy(&value, take(sizeof(T)), sizeof(T));
        return value;
    }
    std::string getString();
    std::vector<uint64_t> getArray();

    std::vector<char>& bytes() { return bytes_; }

private:
    const char* take(size_t n);
    std::vector<char> bytes_;
    size_t read_ = 0;
};

// The measured span inside the child: begin() resets the peak and starts the clocks, end()
// stops them. Called once per timed repeat; the memory is the first span's. Two clocks: the
// wall clock, and the process's CPU time, which a shared machine's other load inflates far
// less (both libraries triangulate on one thread).
class Span {
public:
    void begin();
    void end();
    double medianWallSeconds() const { return median(wall_); }
    double medianCpuSeconds() const { return median(cpu_); }
    uint64_t peakBytes() const { return peak_bytes_; }

private:
    static double median(std::vector<double> values);
    std::vector<double> wall_, cpu_;
    uint64_t peak_bytes_ = 0, rss_at_begin_ = 0;
    double wall_start_ = 0.0, cpu_start_ = 0.0;
};

// The process's CPU time so far (all its threads), in seconds.
double processCpuSeconds();

struct ChildResult {
    std::string failure;  // "" if the child finished; "timeout after N s", "crashed (signal S)" …
    Payload payload;
};

// Forks, runs `body` in the child (which writes what it measured into the payload) and waits,
// killing it after `timeout_s` seconds.
ChildResult runInChild(const std::function<void(Payload&)>& body, uint32_t timeout_s);

}  // namespace bench
