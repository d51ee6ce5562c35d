// Point files in CSV (core/io/point_file.h): x,y then 1 to 4 colour values per line.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <optional>

#include "point_file.h"

namespace ddt {

namespace {

constexpr size_t kMostColumns = 6;  // x, y, r, g, b, a

std::string_view trimmed(std::string_view text) {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) text.remove_suffix(1);
    return text;
}

// The number `text` spells, all of it, else nullopt; `out_of_range` for one beyond double's
// range ("1e999", "1e-999"). from_chars does not depend on the locale (a decimal point always)
// and accepts "nan" and "inf", which the callers then refuse by name.
std::optional<double> numberIn(std::string_view text, bool* out_of_range = nullptr) {
    if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
    double value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (out_of_range) *out_of_range = error == std::errc::result_out_of_range;
    if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return value;
}

// `text` for a one-line message: quoted, at most 24 characters, control characters as '?'.
std::string quoted(std::string_view text) {
    std::string shown(text.substr(0, 24));
    for (char& c : shown)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return "\"" + shown + (text.size() > 24 ? "…\"" : "\"");
}

// The comma-separated fields of `line`, trimmed; `count` may exceed the fields kept.
struct Fields {
    std::array<std::string_view, kMostColumns> field;
    size_t count = 0;
};
Fields fieldsOf(std::string_view line) {
    Fields fields;
    while (true) {
        const size_t comma = line.find(',');
        if (fields.count < kMostColumns) fields.field[fields.count] = trimmed(line.substr(0, comma));
        ++fields.count;
        if (comma == std::string_view::npos) return fields;
        line.remove_prefix(comma + 1);
    }
}

// The first line where something about the colour values was seen, and what.
struct Sighting {
    uint64_t line = 0;  // 0: not seen
    double value = 0;
    void note(uint64_t at, double seen) {
        if (line == 0) line = at, value = seen;
    }
};

}  // namespace

PointSamples parseCsvPoints(const std::string& name, std::string_view text) {
    auto fail = [&](uint64_t line, const std::string& reason) {
        return UserError(name + ": line " + std::to_string(line) + ": " + reason);
    };
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // a UTF-8 byte order mark

    PointSamples points;
    // At most a point a line: the arrays are not reallocated as they fill.
    const size_t lines = std::min<size_t>(std::count(text.begin(), text.end(), '\n') + 1, kMaxPoints);
    points.x.reserve(lines), points.y.reserve(lines);
    size_t columns = 0;  // of the first data line
    uint64_t columns_line = 0;
    Sighting fraction, above_one, above_255;
    bool first_content = true;
    uint64_t line_number = 0;
    while (!text.empty()) {
        const size_t end = text.find('\n');
        const std::string_view line = trimmed(text.substr(0, end));
        text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
        ++line_number;
        if (line.empty() || line.front() == '#') continue;

        const Fields fields = fieldsOf(line);
        // A header of column names: the first content line, when its first field is no number.
        bool out_of_range = false;
        const bool header = first_content && !numberIn(fields.field[0], &out_of_range) && !out_of_range;
        first_content = false;
        if (header) continue;
        if (columns == 0) {
            if (fields.count < 3 || fields.count > kMostColumns)
                throw fail(line_number, std::to_string(fields.count) +
                                            " columns (a point is x,y,v or x,y,v,a or x,y,r,g,b or x,y,r,g,b,a)");
            columns = fields.count, columns_line = line_number;
            points.channels = uint32_t(columns - 2);
            points.values.reserve(lines * points.channels);
        } else if (fields.count != columns) {
            throw fail(line_number, std::to_string(fields.count) + " columns, but line " + std::to_string(columns_line) +
                                        " has " + std::to_string(columns) + " (every point needs the same)");
        }
        if (points.size() == kMaxPoints)
            throw UserError(name + ": more than " + std::to_string(kMaxPoints) + " points (the most ddtup reads)");

        double row[kMostColumns];
        for (size_t k = 0; k < columns; ++k) {
            const std::optional<double> number = numberIn(fields.field[k], &out_of_range);
            if (!number) {
                const std::string column = "column " + std::to_string(k + 1);
                if (fields.field[k].empty()) throw fail(line_number, column + " is empty");
                if (out_of_range) throw fail(line_number, column + " is out of range (" + quoted(fields.field[k]) + ")");
                throw fail(line_number, column + " is not a number (" + quoted(fields.field[k]) + ")");
            }
            row[k] = *number;
        }
        if (std::string problem = coordinateProblem(row[0], row[1]); !problem.empty()) throw fail(line_number, problem);
        points.x.push_back(row[0] + 0.0);  // + 0.0: -0 becomes 0
        points.y.push_back(row[1] + 0.0);
        for (size_t k = 2; k < columns; ++k) {
            // The upper bound waits for the whole file: it decides the scale (point_file.h).
            if (std::string problem = colourProblem(row[k], HUGE_VAL); !problem.empty()) throw fail(line_number, problem);
            if (row[k] != std::floor(row[k])) fraction.note(line_number, row[k]);
            if (row[k] > 1) above_one.note(line_number, row[k]);
            if (row[k] > 255) above_255.note(line_number, row[k]);
            points.values.push_back(float(row[k] + 0.0));
        }
    }
    if (points.size() == 0) throw UserError(name + ": no points (only blank, comment or header lines)");

    auto numberText = [](double value) {
        char digits[32];
        const auto [end, error] = std::to_chars(digits, digits + sizeof(digits), value);
        return std::string(digits, end);
    };
    const bool eight_bit = fraction.line == 0 && above_one.line != 0;
    if (eight_bit) {
        if (above_255.line != 0)
            throw fail(above_255.line, "colour value " + numberText(above_255.value) +
                                           " is above 255 (whole-number values are 8-bit levels 0 to 255)");
        for (float& value : points.values) value /= 255.0f;  // whole numbers up to 255: exact in float
        points.sample_type = SampleType::UInt8;
    } else {
        if (above_one.line != 0)
            throw fail(above_one.line, "colour value " + numberText(above_one.value) +
                                           " is above 1 (values are in [0, 1], or 8-bit levels 0 to 255 when all are "
                                           "whole numbers, but line " + std::to_string(fraction.line) + " has " +
                                           numberText(fraction.value) + ")");
        points.sample_type = SampleType::Float;
    }
    return points;
}

}  // namespace ddt
