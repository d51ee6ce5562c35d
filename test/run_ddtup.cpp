#include "run_ddtup.h"

#include <catch2/catch.hpp>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <fcntl.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

extern char** environ;

namespace {

void fillResult(int status, Run& run) {
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.end_signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
}

// What the tests run as ddtup. With DDTUP_TEST_BACKEND set (`scripts/test --sanitize` sets cpu
// for ThreadSanitizer, which must not watch lavapipe's uninstrumented threads), a script that
// adds --backend DDTUP_TEST_BACKEND to every run that chooses no backend; it finds ddtup in
// DDTUP_TEST_EXECUTABLE.
const char* ddtupCommand() {
    static const std::string script =
        (std::filesystem::path(DDTUP_TEST_DATA).parent_path() / "sanitizers" / "ddtup-with-backend").string();
    return std::getenv("DDTUP_TEST_BACKEND") ? script.c_str() : DDTUP_EXECUTABLE;
}

const std::string kExecutableAssignment = std::string("DDTUP_TEST_EXECUTABLE=") + DDTUP_EXECUTABLE;

}  // namespace

std::string shellQuoted(const std::string& arg) {
    std::string result = "'";
    for (char c : arg) result += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return result + "'";
}

void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::string readFile(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

// The output goes to a folder of its own, so that the folders the tests watch see only what
// ddtup writes.
Run runShell(const std::string& command_line) {
    TempFolder logs;
    const std::string command = "export " + shellQuoted(kExecutableAssignment) + "; DDTUP=" + shellQuoted(ddtupCommand()) +
                                "; { " + command_line + "; } >" + shellQuoted(logs / "out") + " 2>" +
                                shellQuoted(logs / "err");
    const int status = std::system(command.c_str());
    Run run;
    fillResult(status, run);
    run.out = readFile(logs / "out");
    run.err = readFile(logs / "err");
    return run;
}

Run runDdtup(const std::vector<std::string>& args, const std::vector<std::string>& environment,
             const std::string& input_file) {
    std::string command = "env";
    for (const std::string& assignment : environment) command.append(" ").append(shellQuoted(assignment));
    command.append(" \"$DDTUP\"");
    for (const std::string& arg : args) command.append(" ").append(shellQuoted(arg));
    command.append(" <").append(shellQuoted(input_file));
    return runShell(command);
}

void requireOneLineError(const Run& run, int code, const std::string& subject, const std::string& reason) {
    INFO("stderr: " << run.err);
    CHECK(run.exit_code == code);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK((!run.err.empty() && run.err.back() == '\n'));
    CHECK_THAT(run.err, Catch::Contains(subject));
    CHECK_THAT(run.err, Catch::Contains(reason));
    CHECK(run.out.empty());
}

void requireExactError(const Run& run, int code, const std::string& line) {
    CHECK(run.err == "ddtup: " + line + "\n");
    CHECK(run.exit_code == code);
    CHECK(run.out.empty());
}

BackgroundDdtup::BackgroundDdtup(const std::vector<std::string>& args, const std::vector<std::string>& environment,
                                 const std::string& input_file) {
    std::vector<std::string> argv_strings = {ddtupCommand()};
    argv_strings.insert(argv_strings.end(), args.begin(), args.end());
    std::vector<std::string> env_strings(environment);
    env_strings.push_back(kExecutableAssignment);
    for (char** entry = environ; *entry; ++entry) env_strings.emplace_back(*entry);  // earlier ones win
    std::vector<char*> argv, envp;
    for (std::string& arg : argv_strings) argv.push_back(arg.data());
    for (std::string& assignment : env_strings) envp.push_back(assignment.data());
    argv.push_back(nullptr);
    envp.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, input_file.c_str(), O_RDONLY, 0);
    const std::string out = logs_ / "out", err = logs_ / "err";
    posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int result = posix_spawn(&pid_, ddtupCommand(), &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    REQUIRE(result == 0);
}

BackgroundDdtup::~BackgroundDdtup() {
    if (pid_ < 0) return;
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
}

void BackgroundDdtup::signal(int number) { ::kill(pid_, number); }

Run BackgroundDdtup::wait() {
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    Run run;
    fillResult(status, run);
    run.out = readFile(logs_ / "out");
    run.err = readFile(logs_ / "err");
    return run;
}
