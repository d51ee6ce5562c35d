// Talking to OpenImageIO's codecs: their errors as one line for the user, stderr kept quiet
// while they run, ddtup's sample types in OIIO's terms, and a CheckedFile for them to write
// to. Shared by the module's reader and writer.
#pragma once

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <mutex>
#include <string>

#include "checked_file.h"
#include "image.h"

namespace ddt {

// OIIO messages can span lines; the user gets one.
std::string firstLine(std::string message);

// OIIO's per-thread error, for failures that have no ImageInput/ImageOutput to ask.
std::string globalError();

template <class Codec>
std::string codecError(const Codec& codec) {
    return codec.has_error() ? codec.geterror() : globalError();
}

// OIIO 2.4's PNG plugin leaves libpng's default handlers installed, and they print
// "libpng error: …" (and warnings) to stderr on top of the error OIIO returns to us; newer OIIO
// installs its own handlers, 2.4 has no hook for them. The user must get one line, so stderr
// points at /dev/null for the duration of each call into a codec, and only then. Batches read
// and write on two threads at once: the first to enter redirects, the last to leave restores.
class QuietStderr {
public:
    QuietStderr() {
        std::lock_guard lock(mutex_);
        if (users_++ > 0) return;
        std::fflush(stderr);
        int null_fd = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
        if (null_fd < 0) return;
        saved_fd_ = ::fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 0);
        if (saved_fd_ >= 0) ::dup2(null_fd, STDERR_FILENO);
        ::close(null_fd);
    }
    ~QuietStderr() {
        std::lock_guard lock(mutex_);
        if (--users_ > 0 || saved_fd_ < 0) return;
        std::fflush(stderr);
        ::dup2(saved_fd_, STDERR_FILENO);
        ::close(saved_fd_);
        saved_fd_ = -1;
    }
    QuietStderr(const QuietStderr&) = delete;
    QuietStderr& operator=(const QuietStderr&) = delete;

private:
    static inline std::mutex mutex_;
    static inline int users_ = 0;
    static inline int saved_fd_ = -1;
};

// A CheckedFile as OIIO's IOProxy, for its writers to write to (checked_file.h says why).
class CheckedFileProxy final : public OIIO::Filesystem::IOProxy {
public:
    explicit CheckedFileProxy(CheckedFile& file) : IOProxy(file.path(), Write), file_(file) {}

    const char* proxytype() const override { return "ddtup-checked-file"; }
    void close() override {
        file_.close();
        m_mode = Closed;
    }
    size_t write(const void* buf, size_t size) override { return advance(file_.pwrite(buf, size, m_pos)); }
    size_t pwrite(const void* buf, size_t size, int64_t offset) override { return file_.pwrite(buf, size, offset); }
    size_t read(void* buf, size_t size) override { return advance(file_.pread(buf, size, m_pos)); }
    size_t pread(void* buf, size_t size, int64_t offset) override { return file_.pread(buf, size, offset); }
    size_t size() const override { return file_.size(); }

private:
    size_t advance(size_t done) {
        m_pos += int64_t(done);
        return done;
    }
    CheckedFile& file_;
};

SampleType sampleTypeOf(OIIO::TypeDesc format);
OIIO::TypeDesc typeDescOf(SampleType type);

}  // namespace ddt
