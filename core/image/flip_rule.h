// The rules that choose which candidate edges flip together in one parallel iteration:
// the paper's variants (Sec. 3.2 and 5, Table 1's columns) and local-max.
//   basic            accept/reject rounds, lowest id wins, ROI = 2-region
//   exproi           ROI = 3-region in every iteration
//   exproiN-…        3-region in the first N iterations, then the 2-region (ExpROI_N)
//   maxgain          highest gain wins (ties: lowest id)
//   localmax         one round: flip exactly the candidates whose gain is the largest among
//                    the candidates of their 2-region; the rest wait for the next iteration
// The regions are the same for every cost (core/image/cost.h): see glsl/image/select.comp for why variance,
// whose gain has the 1-region as ROI, keeps the 2-region.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ddt {

struct FlipRule {
    std::string name;                // canonical: basic, exproi, maxgain, exproi-maxgain, exproi2-maxgain, localmax, …
    bool key_by_gain = false;        // MaxGain / local-max: higher gain wins
    bool single_round = false;       // local-max
    uint32_t exproi_iterations = 0;  // iterations that use the 3-region (kAlways: all)

    static constexpr uint32_t kAlways = UINT32_MAX;
};

// Accepts the canonical names and exproi-N-maxgain / exproi-N-localmax / exproi-N (N >= 0).
std::optional<FlipRule> parseFlipRule(const std::string& name);

// The rule used when none is given (chosen by measurement: docs/HOW_IT_WORKS.md, "Flip rules").
extern const char* const kDefaultFlipRule;

// The named rules of Table 1 plus local-max, in table order.
std::vector<std::string> tableFlipRules();

}  // namespace ddt
