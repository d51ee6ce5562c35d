// The bench's command line: CLI11 fills BenchOptions; every value is checked before any
// work starts.
#pragma once

#include <optional>

#include "bench_options.h"

namespace bench {

// Returns the options, or the exit code when the program should stop here (--help, or a
// usage error already printed).
std::optional<BenchOptions> parseBenchCommandLine(int argc, char** argv, int& exit_code);

}  // namespace bench
