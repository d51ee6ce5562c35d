#include "process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace fuzz {

ProcessResult runProcess(const std::vector<std::string>& argv, const std::vector<std::string>& environment,
                         const std::string& stderr_path, double timeout_s) {
    // Ours, less the variables `environment` sets (the first of two would win).
    auto setHere = [&](const std::string& entry) {
        for (const std::string& assignment : environment)
            if (entry.compare(0, assignment.find('=') + 1, assignment, 0, assignment.find('=') + 1) == 0) return true;
        return false;
    };
    std::vector<std::string> env_strings;
    for (char** e = environ; *e; ++e)
        if (!setHere(*e)) env_strings.push_back(*e);
    env_strings.insert(env_strings.end(), environment.begin(), environment.end());
    std::vector<char*> env_pointers, arg_pointers;
    for (std::string& s : env_strings) env_pointers.push_back(s.data());
    env_pointers.push_back(nullptr);
    std::vector<std::string> args = argv;
    for (std::string& s : args) arg_pointers.push_back(s.data());
    arg_pointers.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);  // process group = its pid
    posix_spawnattr_setpgroup(&attributes, 0);

    const auto start = std::chrono::steady_clock::now();
    pid_t pid = -1;
    const int error =
        posix_spawn(&pid, arg_pointers[0], &actions, &attributes, arg_pointers.data(), env_pointers.data());
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    if (error) throw std::runtime_error("cannot run " + argv[0] + ": " + std::strerror(error));

    ProcessResult result;
    int status = 0;
    while (true) {
        const pid_t done = waitpid(pid, &status, WNOHANG);
        if (done == pid) break;
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout_s) {
            ::kill(-pid, SIGKILL);
            waitpid(pid, &status, 0);
            result.timed_out = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (result.timed_out) return result;
    if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result.end_signal = WTERMSIG(status);
    return result;
}

}  // namespace fuzz
