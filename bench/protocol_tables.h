// The protocol tables ("Beyond Lanczos") from the raw measurements: means of per-image
// values per protocol, factor and set (each set, then all images), one row per method.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "results.h"
#include "table.h"

namespace bench {

// The mean of `value` over the images of `protocol` at `factor` in `set` ("all images": every
// set) for the method `key`; nothing when there are none or one lacks the method.
std::optional<double> protocolMean(const BenchResults& results, const std::string& protocol, Magnification factor,
                                   const std::string& set, const std::string& key,
                                   const std::function<double(const MethodScores&)>& value);

// PSNR, SSIM, GMSD and overshoot (4 × 4 neighbourhood: mean levels, share over 4 levels) of
// every method: `table3_protocols.csv`.
Table protocolQualityTable(const BenchResults& results);

// The criterion: mean PSNR of consistent DDT minus Lanczos3's (and minus plain
// DDT's), per protocol, factor and set.
Table consistentGainTable(const BenchResults& results);

}  // namespace bench
