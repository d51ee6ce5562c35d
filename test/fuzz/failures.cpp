#include "failures.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace fuzz {

namespace fs = std::filesystem;

namespace {

// "000123-…" (an input and its record) or "batch-…" (a batch's inputs and record).
bool isKeptByUs(const std::string& name) {
    const bool numbered = name.size() > 7 && name[6] == '-' &&
                          std::all_of(name.begin(), name.begin() + 6, [](char c) { return c >= '0' && c <= '9'; });
    return numbered || name.starts_with("batch-");
}

}  // namespace

void clearFailures(const std::string& folder) {
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(folder, error))
        if (isKeptByUs(entry.path().filename().string())) fs::remove_all(entry.path(), error);
}

void saveBatchFailure(const std::string& folder, size_t number, const std::vector<std::string>& inputs,
                      const std::string& record) {
    const fs::path batch = fs::path(folder) / ("batch-" + std::to_string(number));
    fs::create_directories(batch);
    for (const std::string& input : inputs)
        fs::copy_file(input, batch / fs::path(input).filename(), fs::copy_options::overwrite_existing);
    std::ofstream(batch.string() + ".txt") << record;
}

void saveFailure(const std::string& folder, const std::string& input, const std::string& record) {
    fs::create_directories(folder);
    const fs::path target = fs::path(folder) / fs::path(input).filename();
    fs::copy_file(input, target, fs::copy_options::overwrite_existing);
    std::ofstream(target.string() + ".txt") << record;
}

std::vector<std::string> savedInputs(const std::string& folder) {
    std::vector<std::string> inputs;
    for (const auto& entry : fs::directory_iterator(folder))
        if (entry.is_regular_file() && entry.path().extension() != ".txt") inputs.push_back(entry.path().string());
    std::sort(inputs.begin(), inputs.end());
    return inputs;
}

CaseName parseCaseName(const std::string& path) {
    const std::string stem = fs::path(path).stem().string();
    const size_t first = stem.find('-'), second = first == std::string::npos ? first : stem.find('-', first + 1);
    if (second == std::string::npos) return {"?", stem};
    return {stem.substr(first + 1, second - first - 1), stem.substr(second + 1)};
}

std::string caseFileName(size_t index, const std::string& format, const std::string& kind,
                         const std::string& extension) {
    char number[16];
    std::snprintf(number, sizeof number, "%06zu", index);
    return std::string(number) + "-" + format + "-" + kind + extension;
}

}  // namespace fuzz
