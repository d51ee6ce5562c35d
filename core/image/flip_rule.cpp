#include "flip_rule.h"

#include <cctype>

namespace ddt {

const char* const kDefaultFlipRule = "localmax";

namespace {

// Parses "exproi" optionally followed by a count N (as "exproiN" or "exproi-N"), returning
// the iterations with the 3-region and the rest of the name after it.
bool parseExpRoi(const std::string& name, uint32_t& iterations, std::string& rest) {
    const std::string prefix = "exproi";
    if (name.compare(0, prefix.size(), prefix) != 0) return false;
    size_t i = prefix.size();
    if (i < name.size() && name[i] == '-' && i + 1 < name.size() && std::isdigit(static_cast<unsigned char>(name[i + 1])))
        ++i;
    size_t digits_end = i;
    while (digits_end < name.size() && std::isdigit(static_cast<unsigned char>(name[digits_end]))) ++digits_end;
    if (digits_end > i) {
        if (digits_end - i > 6) return false;
        iterations = uint32_t(std::stoul(name.substr(i, digits_end - i)));
    } else {
        iterations = FlipRule::kAlways;
    }
    rest = name.substr(digits_end);
    return true;
}

}  // namespace

std::optional<FlipRule> parseFlipRule(const std::string& name) {
    FlipRule rule;
    std::string rest = name;
    if (parseExpRoi(name, rule.exproi_iterations, rest)) {
        if (rest.empty()) rest = "basic";
        else if (rest[0] == '-') rest = rest.substr(1);
        else return std::nullopt;
    }
    if (rest == "basic") {
    } else if (rest == "maxgain") {
        rule.key_by_gain = true;
    } else if (rest == "localmax") {
        rule.key_by_gain = true;
        rule.single_round = true;
    } else {
        return std::nullopt;
    }
    const std::string base = rest;
    if (rule.exproi_iterations == 0) rule.name = base;
    else if (rule.exproi_iterations == FlipRule::kAlways) rule.name = base == "basic" ? "exproi" : "exproi-" + base;
    else rule.name = "exproi" + std::to_string(rule.exproi_iterations) + (base == "basic" ? "" : "-" + base);
    return rule;
}

std::vector<std::string> tableFlipRules() {
    return {"basic",           "exproi",          "maxgain",  "exproi-maxgain", "exproi2-maxgain",
            "exproi3-maxgain", "exproi4-maxgain", "localmax", "exproi-localmax"};
}

}  // namespace ddt
