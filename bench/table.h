// A table of numbers laid out as the paper prints them, written as Markdown for people
// (section rows in italics, as the paper's) and as CSV for machines (full precision).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace bench {

struct TableRow {
    std::vector<std::string> keys;              // the CSV's leading columns (factor, set …)
    std::string section;                        // Markdown: a section row starts where it changes
    std::string label;                          // what the row measures ("Cost-init.")
    std::vector<std::optional<double>> values;  // one per column; empty: not available
    int decimals = 3;                           // Markdown precision
};

struct Table {
    std::string corner;                  // top-left heading ("Average of")
    std::vector<std::string> key_names;  // CSV headings of TableRow::keys
    std::string label_name;              // CSV heading of the labels
    std::vector<std::string> columns;
    std::vector<TableRow> rows;
};

// Missing values print as "n/a", infinities as "inf", undefined ones as "nan".
std::string toMarkdown(const Table& table);
std::string toCsv(const Table& table);

}  // namespace bench
