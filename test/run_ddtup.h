// Runs the real ddtup executable for the command-line tests.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

#include "temp_folder.h"

struct Run {
    int exit_code = -1;   // -1 when a signal ended it
    int end_signal = 0;   // the signal that ended it, else 0
    std::string out;
    std::string err;
};

// Runs ddtup with `args` (and `environment` assignments such as "LP_NUM_THREADS=1" before it),
// capturing stdout and stderr; standard input comes from `input_file` (default /dev/null).
Run runDdtup(const std::vector<std::string>& args, const std::vector<std::string>& environment = {},
             const std::string& input_file = "/dev/null");

// Runs a shell command line (in which "$DDTUP" names the executable), capturing stdout and
// stderr, for runs that need more than arguments: a mount namespace, a redirection.
Run runShell(const std::string& command_line);

// The environment of a run that finds no Vulkan driver: the loader is pointed at a file that
// does not exist. (Validation, on for the rest of the suite, would report the loader's own
// complaints about that.)
const std::vector<std::string> kNoVulkanDevice = {"VK_DRIVER_FILES=/nonexistent/icd.json",
                                                  "VK_ICD_FILENAMES=/nonexistent/icd.json", "DDTUP_VALIDATION=0"};

// `arg` quoted for the shell.
std::string shellQuoted(const std::string& arg);

// The bytes of a file ("" if it cannot be read).
std::string readFile(const std::string& path);
// Writes `text` as the whole file at `path`.
void writeText(const std::string& path, const std::string& text);

// Exactly one line on stderr that names `subject` and contains `reason`, exit `code`, and
// nothing on stdout.
void requireOneLineError(const Run& run, int code, const std::string& subject, const std::string& reason);

// Exit `code`, stderr exactly "ddtup: " + `line` + "\n", nothing on stdout.
void requireExactError(const Run& run, int code, const std::string& line);

// ddtup started in the background, for tests that signal it.
class BackgroundDdtup {
public:
    explicit BackgroundDdtup(const std::vector<std::string>& args, const std::vector<std::string>& environment = {},
                             const std::string& input_file = "/dev/null");
    ~BackgroundDdtup();  // kills it if it still runs
    BackgroundDdtup(const BackgroundDdtup&) = delete;
    BackgroundDdtup& operator=(const BackgroundDdtup&) = delete;

    void signal(int number);
    // Waits until it ends.
    Run wait();

private:
    TempFolder logs_;
    pid_t pid_ = -1;
};
