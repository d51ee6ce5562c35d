// The paper's Tables 1–3 from the raw measurements: averages over the images of each set at
// each factor (Table 3 also over all images together), one column per method.
#pragma once

#include "results.h"
#include "table.h"

namespace bench {

// Table 1: cost-init, cost-final, improvement, flips and the three stage times (with their
// sum) of CPU DDT and every GPU variant. Improvement is the averaged cost-init over the
// averaged cost-final, × 100 %, as the paper's figures are (1549.901 / 691.641 = 224.09 %).
Table costAndTimeTable(const BenchResults& results);

// Table 2: the time-sum of every GPU variant on every Vulkan device.
Table deviceTimeTable(const BenchResults& results);

// Table 3: PSNR and the paper's six quality metrics of every filter and DDT method.
Table qualityTable(const BenchResults& results);

}  // namespace bench
