// The command line's backends: what --backend auto picks and says, the Vulkan device and its
// messages, the statistics both backends report, and results that do not depend on
// lavapipe's thread count.
#include <catch2/catch.hpp>

#include <filesystem>
#include <algorithm>
#include <set>

#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

std::string fixture(const std::string& name) { return ddt::test::testDataPath(name); }

// The loader sees lavapipe alone: its manifest, whatever the machine's architecture.
std::vector<std::string> onlyLavapipe() {
    for (const auto& entry : std::filesystem::directory_iterator("/usr/share/vulkan/icd.d"))
        if (entry.path().filename().string().starts_with("lvp_icd"))
            return {"VK_DRIVER_FILES=" + entry.path().string(), "VK_ICD_FILENAMES=" + entry.path().string()};
    FAIL("no lavapipe manifest in /usr/share/vulkan/icd.d (mesa-vulkan-drivers)");
    return {};
}

}  // namespace

TEST_CASE("cli: --backend auto without any Vulkan device runs the CPU backend and says so once") {
    TempFolder folder;
    const Run run = runDdtup({fixture("crop32_astronaut.png"), folder / "out.png", "--backend", "auto"}, kNoVulkanDevice);
    CHECK(run.exit_code == 0);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK_THAT(run.err, Catch::Contains("CPU backend") && Catch::Contains("no usable Vulkan device"));
    CHECK(folder.names() == std::set<std::string>{"out.png"});
    const Run quiet =
        runDdtup({fixture("crop32_astronaut.png"), folder / "quiet.png", "--backend", "auto", "-q"}, kNoVulkanDevice);
    CHECK(quiet.exit_code == 0);
    CHECK(quiet.err.empty());
}

TEST_CASE("cli: --backend auto with only lavapipe runs the CPU backend and names the device") {
    TempFolder folder;
    const Run run = runDdtup({fixture("crop32_astronaut.png"), folder / "out.png", "--backend", "auto"}, onlyLavapipe());
    CHECK(run.exit_code == 0);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK_THAT(run.err, Catch::Contains("CPU backend") && Catch::Contains("llvmpipe") && Catch::Contains("--backend vulkan"));
    // The CPU backend's output is the one --backend cpu writes.
    REQUIRE(runDdtup({fixture("crop32_astronaut.png"), folder / "cpu.png", "--backend", "cpu", "-q"}).exit_code == 0);
    CHECK(readFile(folder / "out.png") == readFile(folder / "cpu.png"));
}

TEST_CASE("cli: --device asks for Vulkan under --backend auto") {
    TempFolder folder;
    const Run run = runDdtup({fixture("crop32_astronaut.png"), folder / "out.png", "--backend", "auto", "--device", "0"},
                             onlyLavapipe());
    CHECK(run.exit_code == 0);
    CHECK_THAT(run.err, Catch::Contains("CPU Vulkan device"));
}

TEST_CASE("cli: --backend vulkan without a usable Vulkan device is an error that names the fix") {
    TempFolder folder;
    const Run run = runDdtup({fixture("crop32_astronaut.png"), folder / "out.png", "--backend", "vulkan"}, kNoVulkanDevice);
    requireOneLineError(run, 3, "Vulkan", "mesa-vulkan-drivers");
    CHECK_THAT(run.err, Catch::Contains("--backend cpu"));
    CHECK(folder.names().empty());
}

TEST_CASE("cli: a CPU Vulkan device is announced once, and -q silences it", "[vulkan]") {
    TempFolder folder;
    const Run loud = runDdtup({fixture("crop32_astronaut.png"), folder / "out.png", "--backend", "vulkan"});
    CHECK(loud.exit_code == 0);
    CHECK(std::count(loud.err.begin(), loud.err.end(), '\n') == 1);
    CHECK_THAT(loud.err, Catch::Contains("CPU Vulkan device"));
    const Run quiet = runDdtup({fixture("crop32_astronaut.png"), folder / "out.png", "-q", "--backend", "vulkan"});
    CHECK(quiet.exit_code == 0);
    CHECK(quiet.err.empty());
}

TEST_CASE("cli: --list-devices shows lavapipe as a CPU device", "[vulkan]") {
    const Run run = runDdtup({"--list-devices"});
    CHECK(run.exit_code == 0);
    CHECK_THAT(run.out, Catch::StartsWith("0: "));
    CHECK_THAT(run.out, Catch::Contains("llvmpipe"));
    CHECK_THAT(run.out, Catch::Contains("(CPU,"));
}

TEST_CASE("cli: --stats reports the same figures for both backends", "[vulkan]") {
    TempFolder folder;
    for (const char* backend : {"cpu", "vulkan"}) {
        INFO(backend);
        const Run run = runDdtup({fixture("crop32_astronaut.png"), folder / "out.png", "--stats", "-q", "--backend", backend});
        CHECK(run.exit_code == 0);
        for (const char* line : {"cost-init ", "cost-final ", "improvement ", "flips ", "iterations ", "time-init ",
                                 "time-comp ", "time-final ", "time-sum "})
            CHECK_THAT(run.out, Catch::Contains(line));
        if (std::string(backend) == "vulkan")
            for (const char* line : {"rounds ", "dispatches ", "device-comp "}) CHECK_THAT(run.out, Catch::Contains(line));
    }
}

TEST_CASE("cli: an unknown --variant is a usage error") {
    TempFolder folder;
    requireOneLineError(runDdtup({fixture("crop32_astronaut.png"), folder / "out.png", "--variant", "fastest"}), 2,
                        "--variant", "unknown");
    CHECK(folder.names().empty());
}

TEST_CASE("cli: the output does not depend on lavapipe's thread count", "[vulkan][heavy]") {
    TempFolder folder;
    for (const char* variant : {"localmax", "basic"}) {
        INFO(variant);
        for (const char* threads : {"1", "2"}) {
            const Run run = runDdtup({fixture("crop32_astronaut.png"), folder / (std::string("out") + threads + ".png"),
                                      "-s", "3", "-q", "--variant", variant, "--backend", "vulkan"},
                                     {std::string("LP_NUM_THREADS=") + threads});
            CHECK(run.exit_code == 0);
        }
        CHECK(readFile(folder / "out1.png") == readFile(folder / "out2.png"));
    }
}

TEST_CASE("cli: --backend auto on a machine without a GPU device node does not load Vulkan drivers", "[vulkan]") {
    std::error_code error;
    const bool gpu_nodes = std::filesystem::exists("/dev/dri", error) || std::filesystem::exists("/dev/nvidiactl", error);
    if (gpu_nodes) {
        WARN("this machine has GPU device nodes: the check without them is not run here");
        return;
    }
    TempFolder folder;
    // The note names the reason: no device node, so no driver was asked.
    const Run run = runDdtup({fixture("crop32_astronaut.png"), folder / "out.png", "--backend", "auto"});
    CHECK(run.exit_code == 0);
    CHECK_THAT(run.err, Catch::Contains("CPU backend") && Catch::Contains("no GPU device"));
}
