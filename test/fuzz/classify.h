// From what a ddtup run left (its exit, its --progress=json events on stderr, sanitizer logs,
// the output folder) to an Outcome for each input.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "outcome.h"
#include "process.h"

namespace fuzz {

// The outcome every input of a run shares when the process itself failed (crash, hang,
// sanitizer report), or nothing when it ended normally and the inputs are judged one by one.
// `sanitizer_report` is what the sanitizers logged ("" for nothing).
std::optional<Outcome> processFault(const ProcessResult& process, const std::string& sanitizer_report);

// The outcome of `input` (as named on ddtup's command line) in a run that ended normally,
// from the JSON events in `events` and the files in `output_folder`, where its output is
// `output_name`.
Outcome inputOutcome(const std::string& events, const std::string& input, const std::string& output_folder,
                     const std::string& output_name);

// Lines of stderr that are not JSON events: --progress=json promises there are none.
std::vector<std::string> strayLines(const std::string& events);

}  // namespace fuzz
