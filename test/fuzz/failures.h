// The failures folder: each faulty input kept with a text record, so that
// `ddtup_fuzz --replay FOLDER` (or `scripts/fuzz --replay FOLDER`) runs them again.
#pragma once

#include <string>
#include <vector>

namespace fuzz {

// Removes what an earlier run kept in `folder` (the files named as below), nothing else.
void clearFailures(const std::string& folder);

// Copies `input` into `folder` and writes `record` beside it as NAME.txt.
void saveFailure(const std::string& folder, const std::string& input, const std::string& record);

// For a batch that failed only as a whole: its inputs into `folder`/batch-N/, the record as
// `folder`/batch-N.txt.
void saveBatchFailure(const std::string& folder, size_t number, const std::vector<std::string>& inputs,
                      const std::string& record);

// The inputs kept in `folder`, sorted (the records are passed over).
std::vector<std::string> savedInputs(const std::string& folder);

// Format and damage kind from a damaged file's name, "000123-png-bit-flip.png".
struct CaseName {
    std::string format, kind;
};
CaseName parseCaseName(const std::string& path);
std::string caseFileName(size_t index, const std::string& format, const std::string& kind,
                         const std::string& extension);

}  // namespace fuzz
