#include "gmic_peer.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "image_file.h"

extern char** environ;

namespace bench {

namespace fs = std::filesystem;

namespace {

double childrenCpuSeconds() {
    rusage usage{};
    getrusage(RUSAGE_CHILDREN, &usage);
    auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

// Runs `arguments` (argv[0] is looked up on PATH), its output thrown away; the exit status.
int runQuietly(const std::vector<std::string>& arguments) {
    std::vector<char*> argv;
    for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) return -1;
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

bool gmicAvailable() {
    const char* path = std::getenv("PATH");
    std::stringstream folders(path ? path : "");
    for (std::string folder; std::getline(folders, folder, ':');)
        if (!folder.empty() && access((fs::path(folder) / "gmic").c_str(), X_OK) == 0) return true;
    return false;
}

GmicResult gmicInpaint(const ddt::Image& image, const std::vector<uint32_t>& known, const std::string& command,
                       const std::string& arguments) {
    GmicResult result;
    if (!gmicAvailable()) {
        result.failure = "gmic missing";
        return result;
    }
    const fs::path folder = fs::temp_directory_path() / ("ddtup-bench-delaunay-" + std::to_string(getpid()));
    fs::create_directories(folder);
    const std::string in = folder / "in.png", mask_path = folder / "mask.png", out = folder / "out.png";
    ddt::Image mask;
    mask.width = image.width;
    mask.height = image.height;
    mask.channels = 1;
    mask.pixels.assign(size_t(image.width) * image.height, 1.0f);  // 255: inpaint
    for (uint32_t v : known) mask.pixels[v] = 0.0f;
    ddt::writeImage(in, image);
    ddt::writeImage(mask_path, mask);
    // -v -1: quiet. The result is clamped and rounded to 8-bit values before it is written.
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = childrenCpuSeconds();
    const int status = runQuietly({"gmic", "-v", "-1", in, mask_path, command + "[0]", "[1]" + arguments, "rm[1]",
                                   "cut", "0,255", "round", "o", out});
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.cpu_seconds = childrenCpuSeconds() - cpu_start;
    if (status != 0) {
        result.failure = "gmic failed (" + std::to_string(status) + ")";
    } else {
        result.image = ddt::readImage(out);
        if (result.image.channels != image.channels || result.image.width != image.width)
            result.failure = "gmic wrote another layout";
    }
    fs::remove_all(folder);
    return result;
}

}  // namespace bench
