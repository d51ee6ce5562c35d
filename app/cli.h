// The command line: CLI11 fills Settings; every value is checked before any work starts.
#pragma once

#include <optional>

#include "settings.h"

namespace ddt {

// Returns the settings, or the exit code when the program should stop here (--help,
// --version, or a usage error already printed).
std::optional<Settings> parseCommandLine(int argc, char** argv, int& exit_code);

}  // namespace ddt
