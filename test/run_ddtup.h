// Runs the real ddtup executable for the command-line tests.
#pragma once

#include <string>
#include <vector>

struct Run {
    int exit_code = -1;
    std::string out;
    std::string err;
};

// Runs ddtup with `args` (and `environment` assignments such as "LP_NUM_THREADS=1" before it),
// capturing stdout and stderr.
Run runDdtup(const std::vector<std::string>& args, const std::vector<std::string>& environment = {});

// The bytes of a file ("" if it cannot be read).
std::string readFile(const std::string& path);

// Exactly one line on stderr that names `subject` and contains `reason`, exit `code`, and
// nothing on stdout.
void requireOneLineError(const Run& run, int code, const std::string& subject, const std::string& reason);
