#include "checked_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <limits>
#include <system_error>
#include <vector>

namespace ddt {

namespace {

// Test hook, for machines where no small file system can be mounted: with
// DDTUP_TEST_WRITE_LIMIT=N, a write that would take a file past N bytes fails as on a full
// disk (ENOSPC). The real thing is tested too where `unshare` allows a tmpfs.
uint64_t injectedWriteLimit() {
    const char* limit = std::getenv("DDTUP_TEST_WRITE_LIMIT");
    return limit && *limit ? std::strtoull(limit, nullptr, 10) : std::numeric_limits<uint64_t>::max();
}

}  // namespace

int writeAll(int fd, const void* data, size_t size) {
    for (size_t done = 0; done < size;) {
        const ssize_t n = ::write(fd, static_cast<const char*>(data) + done, size - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return n < 0 ? errno : EIO;
        done += size_t(n);
    }
    return 0;
}

CopyFailure copyAll(int from, const std::function<int(const char* data, size_t size)>& write) {
    std::vector<char> buffer(size_t(1) << 16);
    for (;;) {
        const ssize_t n = ::read(from, buffer.data(), buffer.size());
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return {errno, 0};
        if (n == 0) return {};
        if (const int error = write(buffer.data(), size_t(n))) return {0, error};
    }
}

CheckedFile::CheckedFile(const std::string& path) : path_(path), limit_(injectedWriteLimit()) {
    fd_ = ::open(path.c_str(), O_RDWR | O_TRUNC | O_CLOEXEC);
    if (fd_ < 0) throw std::system_error(errno, std::generic_category());
}

CheckedFile::~CheckedFile() { close(); }

void CheckedFile::close() {
    if (fd_ < 0) return;
    if (::close(fd_) != 0 && !failure_) failure_ = errno;
    fd_ = -1;
}

size_t CheckedFile::write(const void* buf, size_t size) {
    const size_t written = pwrite(buf, size, end_);
    end_ += int64_t(written);
    return written;
}

size_t CheckedFile::pwrite(const void* buf, size_t size, int64_t offset) {
    if (fd_ < 0 || offset < 0) {
        if (!failure_) failure_ = EBADF;
        return 0;
    }
    size_t allowed = size;
    if (uint64_t(offset) + size > limit_) allowed = uint64_t(offset) < limit_ ? size_t(limit_ - uint64_t(offset)) : 0;
    size_t done = 0;
    while (done < allowed) {
        const ssize_t n = ::pwrite(fd_, static_cast<const char*>(buf) + done, allowed - done, offset + int64_t(done));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            if (!failure_) failure_ = n < 0 ? errno : EIO;
            return done;
        }
        done += size_t(n);
    }
    if (done < size && !failure_) failure_ = ENOSPC;  // the injected limit
    return done;
}

size_t CheckedFile::pread(void* buf, size_t size, int64_t offset) const {
    size_t done = 0;
    while (fd_ >= 0 && offset >= 0 && done < size) {
        const ssize_t n = ::pread(fd_, static_cast<char*>(buf) + done, size - done, offset + int64_t(done));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        done += size_t(n);
    }
    return done;
}

size_t CheckedFile::size() const {
    struct stat status {};
    return fd_ >= 0 && ::fstat(fd_, &status) == 0 ? size_t(status.st_size) : 0;
}

}  // namespace ddt
