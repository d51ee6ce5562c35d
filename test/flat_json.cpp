#include "flat_json.h"

#include <catch2/catch.hpp>

#include <sstream>

std::vector<std::map<std::string, std::string>> parseJsonLines(const std::string& text) {
    std::vector<std::map<std::string, std::string>> events;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        INFO("line: " << line);
        std::optional<std::map<std::string, std::string>> event = parseFlatJsonObject(line);
        REQUIRE(event);
        events.push_back(*event);
    }
    return events;
}
