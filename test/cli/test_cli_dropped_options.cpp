// Options that do not apply to a run are refused with one line, or, where the run only learns
// it late (--backend auto choosing the CPU, the default surface under simplification), noted
// on stderr without -v: never dropped without a word.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

const std::string kInput = ddt::test::testDataPath("crop32_astronaut.png");

}  // namespace

TEST_CASE("cli: Vulkan-only options with --backend cpu are refused with one line") {
    TempFolder folder;
    const std::string out = folder / "out.png";
    requireOneLineError(runDdtup({kInput, out, "--backend", "cpu", "--device", "0"}), 2, "--device", "--backend cpu");
    requireOneLineError(runDdtup({kInput, out, "--backend", "cpu", "--no-active-set"}), 2, "--no-active-set",
                        "--backend cpu");
    CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("cli: --no-active-set under --backend auto on the CPU backend is noted") {
    TempFolder folder;
    const Run run = runDdtup({kInput, folder / "out.png", "--no-active-set"}, kNoVulkanDevice);
    INFO(run.err);
    CHECK(run.exit_code == 0);
    CHECK_THAT(run.err, Catch::Contains("using the CPU backend") && Catch::Contains("--no-active-set") &&
                            Catch::Contains("does nothing"));
}

TEST_CASE("cli: the default surface's giving way to the linear one under --simplify is noted") {
    TempFolder folder;
    const Run by_default = runDdtup({kInput, folder / "a.png", "--simplify", "0.5", "--backend", "cpu"});
    INFO(by_default.err);
    CHECK(by_default.exit_code == 0);
    CHECK_THAT(by_default.err, Catch::Contains("rendered with the linear surface"));
    const Run asked = runDdtup({kInput, folder / "b.png", "--simplify", "0.5", "--backend", "cpu", "--reconstruct", "plain"});
    INFO(asked.err);
    CHECK(asked.exit_code == 0);
    CHECK_THAT(asked.err, !Catch::Contains("linear surface"));
}
