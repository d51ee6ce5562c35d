// scripts/ddtup-batch through the real script and the real ddtup: a folder tree with
// sub-folders, names with spaces and non-ASCII characters, and one text file named .png.
// Every run uses --backend cpu: the script is under test here, not the device.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "image_file.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;

const std::string kScript = (fs::path(DDTUP_TEST_DATA).parent_path().parent_path() / "scripts" / "ddtup-batch").string();
const std::string kBad = "sub dir/bad file.png";

// The inputs that must be upscaled, by path under the input folder, and their widths.
const std::map<std::string, uint32_t> kGoodInputs = {
    {"a b.png", 32},
    {"sub dir/c.png", 8},
    {"sub dir/ünï cödé/ß €.PNG", 16},
};

std::string quoted(const std::string& arg) {
    std::string result = "'";
    for (char c : arg) result += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return result + "'";
}

// An input tree, an output folder beside it, and a home folder of its own (GNU parallel keeps
// its files under ~/.parallel).
struct Workspace {
    TempFolder folder;
    std::string in = folder / "in";
    std::string out = folder / "out";
    std::string home = folder / "home";

    Workspace() {
        fs::create_directories(fs::path(in) / "sub dir" / "ünï cödé");
        fs::create_directories(fs::path(in) / ".hidden");
        fs::create_directory(home);
        fs::copy_file(ddt::test::testDataPath("crop32_astronaut.png"), fs::path(in) / "a b.png");
        fs::copy_file(ddt::test::testDataPath("step8_gray.png"), fs::path(in) / "sub dir/c.png");
        fs::copy_file(ddt::test::testDataPath("diag16_rgb.png"), fs::path(in) / "sub dir/ünï cödé/ß €.PNG");
        std::ofstream(fs::path(in) / kBad) << "not an image\n";
        // Neither an image extension nor visible: both ignored.
        std::ofstream(fs::path(in) / "notes.txt") << "notes\n";
        fs::copy_file(ddt::test::testDataPath("step8_gray.png"), fs::path(in) / ".hidden/h.png");
    }

    Run batch(const std::vector<std::string>& args, const std::vector<std::string>& environment = {}) const {
        // SHELL=/bin/sh: a login shell that is not bash, as on many machines (and none at all in
        // CI), must not matter to the script's bash function.
        std::string command = "env SHELL=/bin/sh " + quoted("HOME=" + home) + " " + quoted(std::string("DDTUP=") + DDTUP_EXECUTABLE);
        for (const std::string& assignment : environment) command.append(" ").append(quoted(assignment));
        command.append(" bash ").append(quoted(kScript));
        for (const std::string& arg : args) command.append(" ").append(quoted(arg));
        command.append(" >").append(quoted(folder / "stdout")).append(" 2>").append(quoted(folder / "stderr"));
        const int status = std::system(command.c_str());
        Run run;
        run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        run.out = readFile(folder / "stdout");
        run.err = readFile(folder / "stderr");
        return run;
    }
};

// Every file and folder under `root`, hidden ones included, by relative path.
std::set<std::string> tree(const std::string& root) {
    std::set<std::string> names;
    for (const auto& entry : fs::recursive_directory_iterator(root)) names.insert(fs::relative(entry.path(), root).string());
    return names;
}

std::map<std::string, fs::file_time_type> modificationTimes(const std::string& root) {
    std::map<std::string, fs::file_time_type> times;
    for (const auto& entry : fs::recursive_directory_iterator(root)) times[entry.path().string()] = entry.last_write_time();
    return times;
}

// What ddtup itself says about the bad file, after "ddtup: PATH: ".
std::string ddtupReason(const Workspace& work) {
    const std::string bad = work.in + "/" + kBad;
    const Run run = runDdtup({bad, work.folder / "probe.png", "--backend", "cpu"});
    const std::string prefix = "ddtup: " + bad + ": ";
    REQUIRE(run.exit_code == 1);
    REQUIRE(run.err.rfind(prefix, 0) == 0);
    return run.err.substr(prefix.size(), run.err.find('\n') - prefix.size());
}

// After one run over the fresh workspace: an output for each good input at the same relative
// path, twice its width, nothing else in the output folder (no temporary files), and the bad
// file reported by name with ddtup's reason.
void requireFirstRun(const Workspace& work, const Run& run) {
    INFO("stderr: " << run.err);
    CHECK(run.exit_code == 1);
    std::set<std::string> expected = {"sub dir", "sub dir/ünï cödé"};
    for (const auto& [name, width] : kGoodInputs) {
        expected.insert(name);
        CHECK(ddt::readImage(work.out + "/" + name).width == 2 * width);
    }
    CHECK(tree(work.out) == expected);
    CHECK_THAT(run.err, Catch::Contains("ddtup-batch: summary: 3 done, 0 skipped, 1 failed\n"));
    CHECK_THAT(run.err, Catch::Contains("ddtup-batch: failed: " + work.in + "/" + kBad + ": " + ddtupReason(work) + "\n"));
}

// A second run finds every output in place: nothing is redone, only the bad file again.
void requireResumedRun(const Workspace& work, const std::vector<std::string>& args,
                       const std::vector<std::string>& environment) {
    const auto before = modificationTimes(work.out);
    const Run again = work.batch(args, environment);
    INFO("stderr: " << again.err);
    CHECK(again.exit_code == 1);
    CHECK_THAT(again.err, Catch::Contains("ddtup-batch: summary: 0 done, 3 skipped, 1 failed\n"));
    CHECK(modificationTimes(work.out) == before);
}

bool haveCommand(const std::string& name) { return std::system(("command -v " + name + " >/dev/null").c_str()) == 0; }

}  // namespace

TEST_CASE("ddtup-batch: GNU parallel upscales the tree, reports the bad file and resumes", "[threads]") {
    if (!haveCommand("parallel")) {
        WARN("GNU parallel is not installed (scripts/setup installs it): parallel path not tested");
        return;
    }
    Workspace work;
    const std::vector<std::string> args = {"-j", "2", work.in, work.out, "--", "-s", "2", "--backend", "cpu"};
    requireFirstRun(work, work.batch(args));
    requireResumedRun(work, args, {});
}

TEST_CASE("ddtup-batch: without GNU parallel, xargs does the same", "[threads]") {
    Workspace work;
    const std::vector<std::string> args = {"-j", "2", work.in, work.out, "--", "-s", "2", "--backend", "cpu"};
    requireFirstRun(work, work.batch(args, {"DDTUP_BATCH_NO_PARALLEL=1"}));
    requireResumedRun(work, args, {"DDTUP_BATCH_NO_PARALLEL=1"});
}

// Real remote machines cannot be reached in CI. ":" is GNU parallel's name for this machine,
// so this runs the --sshloginfile command line and the job's local branch.
TEST_CASE("ddtup-batch: --sshloginfile with the local machine", "[threads]") {
    if (!haveCommand("parallel")) {
        WARN("GNU parallel is not installed: --sshloginfile not tested");
        return;
    }
    Workspace work;
    std::ofstream(work.folder / "machines") << ":\n";
    requireFirstRun(work, work.batch({"--sshloginfile", work.folder / "machines", work.in, work.out, "--", "--backend", "cpu"}));
}

// Injected remote machine: an "ssh" that runs the command here, in a folder standing for the
// other machine's home. GNU parallel and rsync really copy each input there, the job runs on
// the copy, the output comes back and the copies are removed; only the network is missing.
TEST_CASE("ddtup-batch: --sshloginfile copies to a machine and back, and cleans up there", "[threads]") {
    if (!haveCommand("parallel") || !haveCommand("rsync")) {
        WARN("GNU parallel or rsync is not installed: transfers to other machines not tested");
        return;
    }
    Workspace work;
    const std::string remote_home = work.folder / "remote-home";
    fs::create_directory(remote_home);
    const std::string fake_ssh = work.folder / "fake-ssh";
    std::ofstream(fake_ssh) << "#!/bin/sh\n"
                               "# ssh [options] HOST [--] COMMAND...: skip the options and the host.\n"
                               "while [ $# -gt 0 ]; do case $1 in -l|-p|-o|-e) shift 2;; -*) shift;; *) break;; esac; done\n"
                               "shift\n"
                               "[ \"$1\" = -- ] && shift\n"
                               "cd " << quoted(remote_home) << " && HOME=" << quoted(remote_home) << " exec bash -c \"$*\"\n";
    fs::permissions(fake_ssh, fs::perms::owner_all);
    std::ofstream(work.folder / "machines") << fake_ssh << " other-machine\n";

    const Run run = work.batch({"--sshloginfile", work.folder / "machines", "--remote-ddtup", DDTUP_EXECUTABLE, work.in,
                                work.out, "--", "--backend", "cpu"});
    requireFirstRun(work, run);
    CHECK(tree(remote_home).empty());
}

TEST_CASE("ddtup-batch: -f names the outputs and refuses two inputs for one output", "[threads]") {
    Workspace work;
    fs::copy_file(ddt::test::testDataPath("step8_gray.png"), fs::path(work.in) / "sub dir/c.tif");
    const Run run = work.batch({"-f", "png", work.in, work.out, "--", "--backend", "cpu"}, {"DDTUP_BATCH_NO_PARALLEL=1"});
    INFO("stderr: " << run.err);
    CHECK(run.exit_code == 1);
    CHECK(fs::exists(work.out + "/sub dir/ünï cödé/ß €.png"));
    CHECK_THAT(run.err, Catch::Contains("ddtup-batch: failed: " + work.in + "/sub dir/c.tif: same output " + work.out +
                                        "/sub dir/c.png as " + work.in + "/sub dir/c.png\n"));
    CHECK_THAT(run.err, Catch::Contains("3 done, 0 skipped, 2 failed"));
}

TEST_CASE("ddtup-batch: options ddtup refuses stop the batch with ddtup's exit code", "[threads]") {
    Workspace work;
    std::vector<std::vector<std::string>> environments = {{"DDTUP_BATCH_NO_PARALLEL=1"}};
    if (haveCommand("parallel")) environments.push_back({});
    for (const std::vector<std::string>& environment : environments) {
        // One process at a time: the first image fails, the other three never start.
        const Run run = work.batch({"-j", "1", work.in, work.out, "--", "--no-such-option"}, environment);
        INFO("stderr: " << run.err);
        CHECK(run.exit_code == 2);
        CHECK_THAT(run.err, Catch::Contains("ddtup-batch: stopped, 3 images not run: ddtup exited with code 2: "));
        CHECK_THAT(run.err, Catch::Contains("--no-such-option"));
        CHECK(tree(work.out).size() <= 1);  // at most the sub-folder made for the first image
    }
}

TEST_CASE("ddtup-batch: bad usage exits 2 and does nothing", "[threads]") {
    Workspace work;
    for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
             {},
             {work.in},
             {work.in, work.in},
             {work.folder / "missing", work.out},
             {"-j", "0", work.in, work.out},
             {"--frobnicate", work.in, work.out},
             {work.in, work.out, "--", "-f", "png"},  // ddtup-batch -f names the outputs
         }) {
        const Run run = work.batch(args);
        INFO("stderr: " << run.err);
        CHECK(run.exit_code == 2);
        CHECK_THAT(run.err, Catch::StartsWith("ddtup-batch: "));
        CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    }
    CHECK(!fs::exists(work.out));

    const Run help = work.batch({"-h"});
    CHECK(help.exit_code == 0);
    CHECK_THAT(help.out, Catch::StartsWith("Usage: ddtup-batch"));
}

// A stand-in ddtup that records its arguments, one per line, and copies its input to its
// output, so the arguments the script gives each process can be read back.
TEST_CASE("ddtup-batch: -j N gives each process its share of the processors, and --threads wins", "[threads]") {
    // What the script divides: the processors nproc counts.
    unsigned cores = 0;
    if (FILE* nproc = ::popen("nproc", "r")) {
        if (std::fscanf(nproc, "%u", &cores) != 1) cores = 0;
        ::pclose(nproc);
    }
    REQUIRE(cores >= 1);
    for (const auto& [extra, expected] :
         {std::pair{std::vector<std::string>{}, std::to_string(std::max(1u, cores / 2))},
          std::pair{std::vector<std::string>{"--threads", "7"}, std::string("7")}}) {
        Workspace work;
        const std::string log = work.folder / "arguments", fake = work.folder / "fake-ddtup";
        std::ofstream(fake) << "#!/bin/sh\nprintf '%s\\n' \"$@\" >>" << quoted(log) << "\ncp \"$1\" \"$2\"\n";
        fs::permissions(fake, fs::perms::owner_all);
        std::vector<std::string> args = {"-j", "2", work.in, work.out, "--", "-s", "2"};
        args.insert(args.end(), extra.begin(), extra.end());
        work.batch(args, {"DDTUP=" + fake, "DDTUP_BATCH_NO_PARALLEL=1"});
        std::ifstream lines(log);
        std::vector<std::string> arguments;
        for (std::string line; std::getline(lines, line);) arguments.push_back(line);
        size_t runs = 0;
        for (size_t i = 0; i + 1 < arguments.size(); ++i)
            if (arguments[i] == "--threads") {
                ++runs;
                CHECK(arguments[i + 1] == expected);
            }
        // One --threads per process: the four images, the bad file among them.
        CHECK(runs == kGoodInputs.size() + 1);
    }
}
