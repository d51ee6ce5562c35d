// Runs a program with a time limit, its stderr into a file.
#pragma once

#include <string>
#include <vector>

namespace fuzz {

struct ProcessResult {
    int exit_code = -1;  // -1 when a signal ended it or it timed out
    int end_signal = 0;  // the signal that ended it (not counting our SIGKILL on a timeout)
    bool timed_out = false;
    double seconds = 0.0;
};

// Runs `argv` in its own process group with `environment` (NAME=value) over ours, standard
// input and output on /dev/null and standard error into `stderr_path`. After `timeout_s`
// seconds the whole group is killed.
ProcessResult runProcess(const std::vector<std::string>& argv, const std::vector<std::string>& environment,
                         const std::string& stderr_path, double timeout_s);

}  // namespace fuzz
