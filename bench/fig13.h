// Fig. 13's outputs: every point as CSV, and two log–log plots of runtime against input
// size (time-sum per method; and the three stages per method).
#pragma once

#include <string>

#include "results.h"

namespace bench {

// Writes fig13.csv, fig13_runtime.svg and fig13_stages.svg into `out_dir`.
void writeFig13(const BenchResults& results, const std::string& out_dir);

}  // namespace bench
