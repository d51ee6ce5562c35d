// --threads and the default thread count: the output does not depend on them, and the
// default follows the processors the process may use.
#include <catch2/catch.hpp>

#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

TEST_CASE("threads: --threads 1 writes the same bytes as the default, on both backends' paths", "[threads]") {
    TempFolder folder;
    const std::string input = ddt::test::testDataPath("crop32_astronaut.png");
    for (const char* mode : {"consistent", "plain"}) {
        INFO(mode);
        const Run one = runDdtup({input, folder / "one.png", "-s", "3", "-q", "--backend", "cpu", "--threads", "1",
                                  "--reconstruct", mode});
        const Run many = runDdtup({input, folder / "many.png", "-s", "3", "-q", "--backend", "cpu", "--threads", "3",
                                   "--reconstruct", mode});
        const Run automatic = runDdtup({input, folder / "auto.png", "-s", "3", "-q", "--backend", "cpu", "--reconstruct", mode});
        REQUIRE(one.exit_code == 0);
        REQUIRE(many.exit_code == 0);
        REQUIRE(automatic.exit_code == 0);
        CHECK(readFile(folder / "one.png") == readFile(folder / "many.png"));
        CHECK(readFile(folder / "one.png") == readFile(folder / "auto.png"));
    }
}

TEST_CASE("threads: the default thread count follows the CPU affinity", "[threads]") {
    TempFolder folder;
    // taskset (util-linux, in every Debian) pins ddtup to one processor; -v names the count.
    const Run run = runShell("taskset -c 0 \"$DDTUP\" " + shellQuoted(ddt::test::testDataPath("crop32_astronaut.png")) +
                             " " + shellQuoted(folder / "out.png") + " --backend cpu -v");
    INFO(run.err);
    CHECK(run.exit_code == 0);
    CHECK_THAT(run.err, Catch::Contains("the CPU backend (1 thread)"));
}

TEST_CASE("threads: --threads must be a positive count", "[threads]") {
    requireOneLineError(runDdtup({"a.png", "b.png", "--threads", "0"}), 2, "--threads", "not in range");
}

TEST_CASE("threads: tiles in parallel write the same bytes as tiles one after another", "[threads]") {
    TempFolder folder;
    const std::string input = ddt::test::testDataPath("crop32_astronaut.png");
    // A 200-pixel photo crop in 64-pixel tiles: four strips of four tiles, each strip's tiles
    // spread over the threads.
    const std::string photo = folder / "photo.png";
    REQUIRE(runDdtup({input, photo, "-s", "6.25", "-q", "--backend", "cpu", "--reconstruct", "plain"}).exit_code == 0);
    for (const char* mode : {"consistent", "plain"}) {
        INFO(mode);
        for (const char* threads : {"1", "3"})
            REQUIRE(runDdtup({photo, folder / (std::string("tiled") + threads + ".png"), "-s", "2", "-q", "--backend", "cpu",
                              "--tile", "64", "--threads", threads, "--reconstruct", mode})
                        .exit_code == 0);
        CHECK(readFile(folder / "tiled1.png") == readFile(folder / "tiled3.png"));
    }
}
