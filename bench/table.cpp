#include "table.h"

#include <cmath>
#include <cstdio>

namespace bench {

namespace {

std::string formatValue(const std::optional<double>& value, const char* format, int decimals) {
    if (!value) return "n/a";
    if (std::isnan(*value)) return "nan";
    if (std::isinf(*value)) return *value > 0 ? "inf" : "-inf";
    char text[64];
    std::snprintf(text, sizeof text, format, decimals, *value);
    return text;
}

std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

}  // namespace

std::string toMarkdown(const Table& table) {
    std::string text = "| " + table.corner + " |";
    std::string rule = "|---|";
    for (const std::string& column : table.columns) {
        text.append(" ").append(column).append(" |");
        rule += "---:|";
    }
    text += "\n" + rule + "\n";
    std::string section;
    for (const TableRow& row : table.rows) {
        if (row.section != section && !row.section.empty()) {
            text += "| *" + row.section + "* |" + std::string(table.columns.size(), '|') + "\n";
            section = row.section;
        }
        text.append("| ").append(row.label).append(" |");
        for (const std::optional<double>& value : row.values)
            text.append(" ").append(formatValue(value, "%.*f", row.decimals)).append(" |");
        text += "\n";
    }
    return text;
}

std::string toCsv(const Table& table) {
    std::string text;
    for (const std::string& key : table.key_names) text += csvField(key) + ",";
    text += csvField(table.label_name);
    for (const std::string& column : table.columns) text.append(",").append(csvField(column));
    text += "\n";
    for (const TableRow& row : table.rows) {
        for (const std::string& key : row.keys) text += csvField(key) + ",";
        text += csvField(row.label);
        // %.*g with 10 significant digits: exact enough to recompute every derived figure.
        for (const std::optional<double>& value : row.values) text.append(",").append(formatValue(value, "%.*g", 10));
        text += "\n";
    }
    return text;
}

}  // namespace bench
