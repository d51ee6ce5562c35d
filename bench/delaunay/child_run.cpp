#include "child_run.h"

#include <malloc.h>
#include <signal.h>
#include <time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace bench {

namespace {

double nowSeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// A "VmXXX:   1234 kB" line of /proc/self/status, in bytes.
uint64_t statusBytes(const std::string& field) {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.compare(0, field.size() + 1, field + ":") == 0) return std::stoull(line.substr(field.size() + 1)) * 1024;
    throw std::runtime_error("no " + field + " in /proc/self/status");
}

void writeAll(int fd, const char* data, size_t size) {
    while (size > 0) {
        const ssize_t n = write(fd, data, size);
        if (n <= 0) _exit(3);
        data += n;
        size -= size_t(n);
    }
}

}  // namespace

void Payload::putString(const std::string& text) {
    put<uint64_t>(text.size());
    bytes_.insert(bytes_.end(), text.begin(), text.end());
}

void Payload::putArray(const std::vector<uint64_t>& values) {
    put<uint64_t>(values.size());
    if (values.empty()) return;  // data() may be null, and null + 0 is not for insert's range
    const char* p = reinterpret_cast<const char*>(values.data());
    bytes_.insert(bytes_.end(), p, p + values.size() * sizeof(uint64_t));
}

const char* Payload::take(size_t n) {
    if (read_ + n > bytes_.size()) throw std::runtime_error("child payload too short");
    const char* p = bytes_.data() + read_;
    read_ += n;
    return p;
}

std::string Payload::getString() {
    const uint64_t n = get<uint64_t>();
    return std::string(take(n), n);
}

std::vector<uint64_t> Payload::getArray() {
    const uint64_t n = get<uint64_t>();
    std::vector<uint64_t> values(n);
    const char* p = take(n * sizeof(uint64_t));
    // An empty vector's data() may be null, which memcpy must not get even for zero bytes.
    if (n > 0) std::memcpy(values.data(), p, n * sizeof(uint64_t));
    return values;
}

double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

void Span::begin() {
    if (wall_.empty()) {
        // Resets VmHWM to the current VmRSS (Linux ≥ 4.0, proc(5)).
        std::ofstream clear("/proc/self/clear_refs");
        clear << "5";
        clear.close();
        if (!clear) throw std::runtime_error("cannot reset the peak RSS through /proc/self/clear_refs");
        rss_at_begin_ = statusBytes("VmRSS");
    }
    wall_start_ = nowSeconds();
    cpu_start_ = processCpuSeconds();
}

void Span::end() {
    cpu_.push_back(processCpuSeconds() - cpu_start_);
    wall_.push_back(nowSeconds() - wall_start_);
    if (wall_.size() == 1) peak_bytes_ = statusBytes("VmHWM") - rss_at_begin_;
}

double Span::median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values.empty() ? 0.0 : values[values.size() / 2];
}

ChildResult runInChild(const std::function<void(Payload&)>& body, uint32_t timeout_s) {
    ChildResult result;
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
    std::fflush(nullptr);  // or the child's exit would print the parent's buffered output again
    malloc_trim(0);        // freed heap pages go back, so that the child does not start on them
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        close(fds[0]);
        alarm(timeout_s);
        Payload payload;
        try {
            body(payload);
        } catch (const std::exception& error) {
            std::fprintf(stderr, "ddtup-bench-delaunay: child: %s\n", error.what());
            _exit(2);
        }
        const uint64_t size = payload.bytes().size();
        writeAll(fds[1], reinterpret_cast<const char*>(&size), sizeof size);
        writeAll(fds[1], payload.bytes().data(), size);
        _exit(0);  // no destructors: they would only free what the exit frees anyway, slowly
    }
    close(fds[1]);
    std::vector<char> received;
    char buffer[1 << 16];
    for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) != 0;) {
        if (n < 0) {
            if (errno == EINTR) continue;
            break;
        }
        received.insert(received.end(), buffer, buffer + n);
    }
    close(fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    if (WIFSIGNALED(status)) {
        result.failure = WTERMSIG(status) == SIGALRM ? "timeout after " + std::to_string(timeout_s) + " s"
                                                      : "crashed (signal " + std::to_string(WTERMSIG(status)) + ")";
        return result;
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || received.size() < sizeof(uint64_t)) {
        result.failure = "failed (exit " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")";
        return result;
    }
    result.payload.bytes().assign(received.begin() + sizeof(uint64_t), received.end());
    return result;
}

}  // namespace bench
