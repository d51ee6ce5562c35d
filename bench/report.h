// The bench's output folder: report.md (every table, the reference check, Fig. 13 and the
// crops, with what each figure means), table1/2/3.csv, fig13.csv and its SVG plots, and
// measurements.json with every raw measurement.
#pragma once

#include <string>

#include "results.h"

namespace bench {

void writeReport(const BenchResults& results, const std::string& out_dir);

}  // namespace bench
