// The whole bench as one recipe: find the sets, run every method on every image at every
// factor (Tables 1–3, crops), measure runtime against size (Fig. 13), write the report.
#pragma once

#include "bench_options.h"

namespace bench {

// Prints progress to stdout. Throws UserError for unusable data or output folders.
void runBench(const BenchOptions& options);

}  // namespace bench
