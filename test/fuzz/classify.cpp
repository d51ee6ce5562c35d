#include "classify.h"

#include <filesystem>
#include <sstream>

#include "flat_json.h"

namespace fuzz {

namespace {

namespace fs = std::filesystem;

// The exit code the fuzzer gives the sanitizers (ASAN_OPTIONS=exitcode=…), unlike ddtup's own.
constexpr int kSanitizerExitCode = 86;

using Event = std::map<std::string, std::string>;

std::vector<Event> eventsOf(const std::string& text) {
    std::vector<Event> events;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);)
        if (std::optional<Event> event = parseFlatJsonObject(line)) events.push_back(*event);
    return events;
}

std::string field(const Event& event, const std::string& name) {
    const auto it = event.find(name);
    return it == event.end() ? std::string() : it->second;
}

// A message of the documented form "NAME: reason", NAME the input or its output.
bool namesItsFile(const std::string& message, const std::string& input, const std::string& output) {
    for (const std::string& name : {input, output})
        if (message.size() > name.size() + 2 && message.compare(0, name.size() + 2, name + ": ") == 0) return true;
    return false;
}

// The output, or ddtup's temporary file for it (".NAME.ddtup…"), in the output folder.
bool leftSomething(const std::string& output_folder, const std::string& output_name) {
    std::error_code error;
    if (fs::exists(fs::path(output_folder) / output_name, error)) return true;
    const std::string temporary = "." + output_name + ".ddtup";
    for (const auto& entry : fs::directory_iterator(output_folder, error))
        if (entry.path().filename().string().starts_with(temporary)) return true;
    return false;
}

}  // namespace

const char* outcomeName(Outcome outcome) {
    switch (outcome) {
        case Outcome::Accepted: return "accepted";
        case Outcome::Refused: return "refused";
        case Outcome::Crash: return "crash";
        case Outcome::Hang: return "hang";
        case Outcome::Sanitizer: return "sanitizer";
        case Outcome::SilentRefusal: return "silent refusal";
        case Outcome::LeftFile: return "left file";
        case Outcome::InternalError: return "internal error";
    }
    return "?";
}

std::optional<Outcome> processFault(const ProcessResult& process, const std::string& sanitizer_report) {
    if (!sanitizer_report.empty() || process.exit_code == kSanitizerExitCode) return Outcome::Sanitizer;
    if (process.timed_out) return Outcome::Hang;
    if (process.end_signal) return Outcome::Crash;
    // 0 every image done, 1 some failed, 4 an internal error (judged per input).
    if (process.exit_code == 0 || process.exit_code == 1 || process.exit_code == 4) return std::nullopt;
    return Outcome::Crash;
}

Outcome inputOutcome(const std::string& events_text, const std::string& input, const std::string& output_folder,
                     const std::string& output_name) {
    const std::string output = (fs::path(output_folder) / output_name).string();
    bool done = false;
    std::optional<std::string> error;
    for (const Event& event : eventsOf(events_text)) {
        if (field(event, "input") != input) continue;
        if (field(event, "event") == "done") done = true;
        if (field(event, "event") == "error") error = field(event, "message");
    }
    std::error_code ignored;
    if (done && !error) return fs::exists(output, ignored) ? Outcome::Accepted : Outcome::SilentRefusal;
    if (!error || !namesItsFile(*error, input, output)) return Outcome::SilentRefusal;
    if (error->find(": internal error") != std::string::npos) return Outcome::InternalError;
    return leftSomething(output_folder, output_name) ? Outcome::LeftFile : Outcome::Refused;
}

std::vector<std::string> strayLines(const std::string& events_text) {
    std::vector<std::string> stray;
    std::istringstream lines(events_text);
    for (std::string line; std::getline(lines, line);)
        if (!parseFlatJsonObject(line)) stray.push_back(line);
    return stray;
}

}  // namespace fuzz
