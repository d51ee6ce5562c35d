// The raw measurements as JSON: every image, method and timed run, the machine, and what
// each figure means, so any table or plot can be recomputed without running the bench.
#pragma once

#include <string>

#include "results.h"

namespace bench {

std::string measurementsJson(const BenchResults& results);

}  // namespace bench
