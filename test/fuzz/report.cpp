#include "report.h"

#include <cstring>

namespace fuzz {

void Report::addRow(const std::string& format, const std::string& kind) { row(format, kind); }

Report::Row& Report::row(const std::string& format, const std::string& kind) {
    for (Row& r : rows_)
        if (r.format == format && r.kind == kind) return r;
    rows_.push_back({format, kind, {}});
    return rows_.back();
}

void Report::count(const std::string& format, const std::string& kind, Outcome outcome) {
    ++row(format, kind).counts[size_t(outcome)];
}

int Report::faults() const {
    int faults = batch_faults_;
    for (const Row& r : rows_)
        for (Outcome outcome : kOutcomes)
            if (isFault(outcome)) faults += r.counts[size_t(outcome)];
    return faults;
}

int Report::inputs() const {
    int inputs = 0;
    for (const Row& r : rows_)
        for (int count : r.counts) inputs += count;
    return inputs;
}

void Report::print(std::FILE* out) const {
    // Each column as wide as its heading.
    auto line = [&](const std::string& format, const std::string& kind, int count,
                    const std::array<int, kOutcomeCount>& counts) {
        std::fprintf(out, "%-8s %-13s %6d", format.c_str(), kind.c_str(), count);
        for (Outcome outcome : kOutcomes)
            std::fprintf(out, "  %*d", int(std::strlen(outcomeName(outcome))), counts[size_t(outcome)]);
        std::fprintf(out, "\n");
    };
    std::fprintf(out, "%-8s %-13s %6s", "format", "damage", "count");
    for (Outcome outcome : kOutcomes) std::fprintf(out, "  %s", outcomeName(outcome));
    std::fprintf(out, "\n");
    std::array<int, kOutcomeCount> totals{};
    for (const Row& r : rows_) {
        int sum = 0;
        for (size_t i = 0; i < r.counts.size(); ++i) sum += r.counts[i], totals[i] += r.counts[i];
        if (sum) line(r.format, r.kind, sum, r.counts);
    }
    line("total", "", inputs(), totals);
    if (batch_faults_) std::fprintf(out, "batches that failed only as a whole: %d\n", batch_faults_);
}

}  // namespace fuzz
