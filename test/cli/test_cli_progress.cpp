// Progress through the real executable: --progress=json is nothing but JSON events (errors and
// notes included), a forced progress line redraws in place, and without a terminal the
// default is silence.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "flat_json.h"
#include "run_ddtup.h"
#include "temp_folder.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;

const std::string kSample = ddt::test::testDataPath("crop32_astronaut.png");

using Event = std::map<std::string, std::string>;

std::vector<Event> eventsNamed(const std::vector<Event>& events, const std::string& name) {
    std::vector<Event> found;
    for (const Event& event : events)
        if (event.at("event") == name) found.push_back(event);
    return found;
}

}  // namespace

TEST_CASE("progress: json mode writes only JSON events, errors and notes among them") {
    TempFolder folder;
    fs::copy_file(kSample, folder / "a.png");
    fs::copy_file(kSample, folder / "c.png");
    std::ofstream(folder / "b.png") << "not an image";
    const std::string out = folder / "out";
    const Run run = runDdtup({folder / "a.png", folder / "b.png", folder / "c.png", "-o", out, "--progress=json"});
    CHECK(run.exit_code == 1);
    CHECK(run.out.empty());
    const std::vector<Event> events = parseJsonLines(run.err);
    REQUIRE(!events.empty());
    for (const Event& event : events) REQUIRE(event.count("event"));

    CHECK(events.front().at("event") == "start");
    CHECK(events.front().at("images") == "3");
    const Event& summary = events.back();
    CHECK(summary.at("event") == "summary");
    CHECK(summary.at("done") == "2");
    CHECK(summary.at("failed") == "1");
    CHECK(summary.at("exit_code") == "1");

    const std::vector<Event> errors = eventsNamed(events, "error");
    REQUIRE(errors.size() == 1);
    CHECK(errors[0].at("input") == folder / "b.png");
    CHECK_THAT(errors[0].at("message"), Catch::StartsWith(folder / "b.png" + ": "));

    const std::vector<Event> done = eventsNamed(events, "done");
    REQUIRE(done.size() == 2);
    CHECK(done[0].at("input") == folder / "a.png");
    CHECK(done[0].at("output") == out + "/a.png");
    CHECK(done[0].at("width") == "64");
    CHECK(done[1].at("index") == "2");
    // The backend choice (with the reason under --backend auto) is an event too, not a notice.
    const std::vector<Event> devices = eventsNamed(events, "device");
    REQUIRE(devices.size() == 1);
    CHECK(devices[0].count("backend") == 1);
    CHECK(eventsNamed(events, "notice").empty());
    // Every image passes through the stages in order.
    std::vector<std::string> stages_of_a;
    for (const Event& event : eventsNamed(events, "stage"))
        if (event.at("index") == "0") stages_of_a.push_back(event.at("stage"));
    CHECK(stages_of_a == std::vector<std::string>{"read", "optimize", "render", "write"});
    const std::vector<Event> progress = eventsNamed(events, "progress");
    REQUIRE(!progress.empty());
    CHECK(progress.back().at("done") == "2");
    CHECK(progress.back().at("total") == "3");
}

TEST_CASE("progress: a usage error in json mode is a JSON event too", "[threads]") {
    const Run run = runDdtup({"--progress=json", "--scale", "0", "a.png", "b.png"});
    CHECK(run.exit_code == 2);
    const std::vector<Event> events = parseJsonLines(run.err);
    REQUIRE(events.size() == 1);
    CHECK(events[0].at("event") == "error");
    CHECK_THAT(events[0].at("message"), Catch::Contains("--scale must be a number >= 1"));
    CHECK(events[0].at("exit_code") == "2");
    // CLI11's own errors too.
    const std::vector<Event> unknown = parseJsonLines(runDdtup({"--progress", "json", "--frobnicate"}).err);
    REQUIRE(unknown.size() == 1);
    CHECK_THAT(unknown[0].at("message"), Catch::Contains("--frobnicate"));
}

TEST_CASE("progress: a forced progress line names the image and stage, and is off without a terminal", "[threads]") {
    TempFolder folder;
    fs::copy_file(kSample, folder / "a.png");
    fs::copy_file(kSample, folder / "b.png");
    const std::vector<std::string> batch = {folder / "a.png", folder / "b.png", "-o", folder / "out"};

    std::vector<std::string> forced = batch;
    forced.push_back("--progress=bar");
    const Run bar = runDdtup(forced);
    CHECK(bar.exit_code == 0);
    CHECK_THAT(bar.err, Catch::Contains("\r\033[K[1/2] " + folder / "a.png" + ": optimize"));
    CHECK_THAT(bar.err, Catch::Contains("[2/2] " + folder / "b.png" + ": write"));
    CHECK_THAT(bar.err, Catch::Contains("elapsed"));
    // The line is cleared before the summary, so the terminal ends clean.
    CHECK_THAT(bar.err, Catch::Contains("\r\033[Kddtup: summary: 2 done"));

    const Run plain = runDdtup(batch);  // stderr is a file here, not a terminal
    CHECK(plain.exit_code == 0);
    CHECK(plain.err.find('\r') == std::string::npos);
}
