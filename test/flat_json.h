// Reads the --progress=json events in tests: one flat JSON object per line, whose values are
// strings, numbers or null. Strict enough to fail on anything that is not valid JSON.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

// The object's fields with their values as written (strings unescaped, numbers as text), or
// nothing when `line` is not one flat JSON object.
std::optional<std::map<std::string, std::string>> parseFlatJsonObject(const std::string& line);

// Every line of `text` parsed; a line that does not parse fails the calling test.
std::vector<std::map<std::string, std::string>> parseJsonLines(const std::string& text);
