// Temporary files that must not outlive the process: an image being written beside its
// output, the copy of standard input. Each live one is listed where a signal handler can read
// it, so Ctrl-C removes them as well as a normal exit or a failure does.
#pragma once

#include <string>

namespace ddt {

// An empty file created for the caller, removed by the destructor unless release() was
// called (after it was renamed into place).
class TempFile {
public:
    // Creates `folder`/`prefix`-PID-N exclusively. Throws std::system_error with the reason.
    TempFile(const std::string& folder, const std::string& prefix);
    ~TempFile();
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;

    const std::string& path() const { return path_; }
    // The file is no longer ours to remove (it was renamed to its final name).
    void release();

private:
    std::string path_;
    int slot_ = -1;  // in the signal handler's list; -1 when the list was full
};

// The system's temporary folder ($TMPDIR, else /tmp): where files not tied to an output folder go.
std::string tempFolder();

// On SIGINT, SIGTERM, SIGHUP or SIGPIPE: removes every live TempFile, then dies of the signal
// as if there were no handler (so the exit status is 128 + the signal's number). Call once,
// from main.
void installInterruptCleanup();

}  // namespace ddt
