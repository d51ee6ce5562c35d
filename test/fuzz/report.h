// The counts table: one row per format × damage kind, a column per outcome, and totals.
#pragma once

#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "outcome.h"

namespace fuzz {

class Report {
public:
    // Rows print in the order they are first named.
    void addRow(const std::string& format, const std::string& kind);
    void count(const std::string& format, const std::string& kind, Outcome outcome);
    // Inputs that failed only together, in one process, and alone did not.
    void countBatchFault() { ++batch_faults_; }

    int faults() const;
    int inputs() const;
    void print(std::FILE* out) const;

private:
    struct Row {
        std::string format, kind;
        std::array<int, kOutcomeCount> counts{};
    };
    Row& row(const std::string& format, const std::string& kind);

    std::vector<Row> rows_;
    int batch_faults_ = 0;
};

}  // namespace fuzz
