#include "run_ddtup.h"

#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "temp_folder.h"

namespace {

std::string quoted(const std::string& arg) {
    std::string result = "'";
    for (char c : arg) result += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return result + "'";
}

}  // namespace

std::string readFile(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

// The output goes to a folder of its own, so that the folders the tests watch see only what
// ddtup writes.
Run runDdtup(const std::vector<std::string>& args, const std::vector<std::string>& environment) {
    TempFolder logs;
    std::string command = "env";
    for (const std::string& assignment : environment) command.append(" ").append(quoted(assignment));
    command.append(" ").append(quoted(DDTUP_EXECUTABLE));
    for (const std::string& arg : args) command.append(" ").append(quoted(arg));
    command.append(" >").append(quoted(logs / "out")).append(" 2>").append(quoted(logs / "err"));
    const int status = std::system(command.c_str());
    Run run;
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.out = readFile(logs / "out");
    run.err = readFile(logs / "err");
    return run;
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

