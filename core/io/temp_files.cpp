#include "temp_files.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <system_error>

namespace ddt {

namespace {

// The list the signal handler reads. A handler may only call async-signal-safe functions, so
// it is a fixed array of C strings with lock-free states, and the handler does nothing but
// unlink. A batch keeps a few files open at a time (one per image in flight, plus stdin).
enum SlotState : int { kFree, kFilling, kLive };
struct Slot {
    std::atomic<int> state{kFree};
    char path[PATH_MAX];
};
const int kSlots = 64;
Slot slots[kSlots];
std::mutex slots_mutex;  // between threads that add and remove; the handler never waits for it

static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

int addToList(const std::string& path) {
    if (path.size() >= PATH_MAX) return -1;
    std::lock_guard<std::mutex> lock(slots_mutex);
    for (int i = 0; i < kSlots; ++i) {
        if (slots[i].state.load() != kFree) continue;
        slots[i].state.store(kFilling);
        std::memcpy(slots[i].path, path.c_str(), path.size() + 1);
        slots[i].state.store(kLive, std::memory_order_release);
        return i;
    }
    return -1;  // the file is still removed by its destructor, only not on a signal
}

void removeFromList(int slot) {
    if (slot < 0) return;
    std::lock_guard<std::mutex> lock(slots_mutex);
    slots[slot].state.store(kFree);
}

extern "C" void removeTempFilesAndDie(int signal_number) {
    const int saved_errno = errno;
    for (Slot& slot : slots)
        if (slot.state.load(std::memory_order_acquire) == kLive) ::unlink(slot.path);
    errno = saved_errno;
    // SA_RESETHAND has restored the default action; the signal is blocked until this handler
    // returns, and then ends the process with the signal's own status.
    ::raise(signal_number);
}

std::atomic<unsigned> next_suffix{0};

}  // namespace

TempFile::TempFile(const std::string& folder, const std::string& prefix) {
    const std::string stem = folder + "/" + prefix + "-" + std::to_string(::getpid()) + "-";
    for (int attempt = 0;; ++attempt) {
        path_ = stem + std::to_string(next_suffix++);
        // Listed before it exists, so that no signal can come between creating and listing it.
        slot_ = addToList(path_);
        const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            ::close(fd);
            return;
        }
        const int error = errno;
        removeFromList(slot_);
        if (error != EEXIST || attempt == 99) throw std::system_error(error, std::generic_category());
    }
}

TempFile::~TempFile() {
    if (path_.empty()) return;
    ::unlink(path_.c_str());
    removeFromList(slot_);
}

void TempFile::release() {
    removeFromList(slot_);
    path_.clear();
}

std::string tempFolder() {
    std::error_code error;
    const std::filesystem::path folder = std::filesystem::temp_directory_path(error);
    return error ? "/tmp" : folder.string();
}

void installInterruptCleanup() {
    struct sigaction action {};
    action.sa_handler = removeTempFilesAndDie;
    action.sa_flags = SA_RESETHAND;
    sigemptyset(&action.sa_mask);
    // SIGPIPE: `ddtup in.png - | head -c 10` closes our standard output mid-copy.
    for (int signal_number : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
        struct sigaction previous {};
        sigaction(signal_number, nullptr, &previous);
        // A signal the caller ignores (nohup, a background job) stays ignored.
        if (previous.sa_handler != SIG_IGN) sigaction(signal_number, &action, nullptr);
    }
}

}  // namespace ddt
