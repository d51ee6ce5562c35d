// Writes whose every failure is seen. CheckedFile is the file every writer of ddtup writes to:
// its own encoders directly, OpenImageIO's codecs through an IOProxy (oiio_codec.h).
// OIIO 2.4's PNG, BMP and Targa writers ignore failed writes: on a full disk they report
// success and leave a truncated file (measured on a 64 KiB tmpfs), so the writer asks this
// file instead of the codec whether everything reached the disk.
#pragma once

#include <cstddef>
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

class CheckedFile {
public:
    // Opens an existing file for writing (and reading back), emptied. Throws std::system_error.
    explicit CheckedFile(const std::string& path);
    ~CheckedFile();
    CheckedFile(const CheckedFile&) = delete;
    CheckedFile& operator=(const CheckedFile&) = delete;

    const std::string& path() const { return path_; }
    void close();
    // At the end of what write() wrote before.
    size_t write(const void* buf, size_t size);
    size_t pwrite(const void* buf, size_t size, int64_t offset);
    // Codecs read back what they wrote (libtiff, when it adds a directory).
    size_t pread(void* buf, size_t size, int64_t offset) const;
    size_t size() const;

    // errno of the first write or close that failed; 0 if none did.
    int failure() const { return failure_; }

private:
    std::string path_;
    int fd_ = -1;
    int failure_ = 0;
    int64_t end_ = 0;  // where write() goes on
    uint64_t limit_;   // bytes this file may hold: the test hook, else no limit
};

}  // namespace ddt
