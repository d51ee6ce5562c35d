// Writes whose every failure is seen. CheckedFile is the file an ImageWriter's codec writes to,
// through OIIO's IOProxy.
// OIIO 2.4's PNG, BMP and Targa writers ignore failed writes: on a full disk they report
// success and leave a truncated file (measured on a 64 KiB tmpfs), so the writer asks this
// file instead of the codec whether everything reached the disk.
#pragma once

#include <OpenImageIO/filesystem.h>

#include <cstdint>
#include <functional>
#include <string>

namespace ddt {

// Writes all `size` bytes to `fd`, retrying short writes and EINTR; 0, or errno of the
// failure (EIO when the file takes nothing).
int writeAll(int fd, const void* data, size_t size);

// Reads `from` to its end and hands each piece to `write(data, size)`, which returns 0 or the
// errno of its failure. Stops at the first failure of either side.
struct CopyFailure {
    int read_error = 0;   // errno of a failed read of `from`
    int write_error = 0;  // what `write` returned
};
CopyFailure copyAll(int from, const std::function<int(const char* data, size_t size)>& write);

class CheckedFile final : public OIIO::Filesystem::IOProxy {
public:
    // Opens an existing file for writing (and reading back), emptied. Throws std::system_error.
    explicit CheckedFile(const std::string& path);
    ~CheckedFile() override;

    const char* proxytype() const override { return "ddtup-checked-file"; }
    void close() override;
    size_t write(const void* buf, size_t size) override;
    size_t pwrite(const void* buf, size_t size, int64_t offset) override;
    // libtiff reads back what it wrote when it adds a directory (EXIF, for one).
    size_t read(void* buf, size_t size) override;
    size_t pread(void* buf, size_t size, int64_t offset) override;
    size_t size() const override;

    // errno of the first write or close that failed; 0 if none did.
    int failure() const { return failure_; }

private:
    int fd_ = -1;
    int failure_ = 0;
    uint64_t limit_;  // bytes this file may hold: the test hook, else no limit
};

}  // namespace ddt
