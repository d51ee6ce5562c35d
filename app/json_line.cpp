#include "json_line.h"

#include <cmath>
#include <cstdio>

namespace ddt {

namespace {

// The length of the valid UTF-8 sequence starting at text[i], or 0.
size_t utf8Length(const std::string& text, size_t i) {
    const unsigned char lead = static_cast<unsigned char>(text[i]);
    size_t length = lead < 0x80 ? 1 : (lead >> 5) == 0x6 ? 2 : (lead >> 4) == 0xE ? 3 : (lead >> 3) == 0x1E ? 4 : 0;
    if (length == 0 || i + length > text.size()) return 0;
    for (size_t k = 1; k < length; ++k)
        if ((static_cast<unsigned char>(text[i + k]) >> 6) != 0x2) return 0;
    return length;
}

}  // namespace

std::string jsonString(const std::string& text) {
    std::string quoted = "\"";
    for (size_t i = 0; i < text.size();) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        const size_t length = utf8Length(text, i);
        if (length == 0) {
            quoted += "\\ufffd";
            ++i;
            continue;
        }
        if (c == '"' || c == '\\') {
            quoted += '\\';
            quoted += char(c);
        } else if (c < 0x20) {
            char escape[8];
            std::snprintf(escape, sizeof escape, "\\u%04x", c);
            quoted += escape;
        } else {
            quoted.append(text, i, length);
        }
        i += length;
    }
    return quoted + "\"";
}

void JsonLine::name(const std::string& name) {
    text_ += text_.empty() ? "{" : ",";
    text_ += jsonString(name) + ":";
}

JsonLine& JsonLine::field(const std::string& name, const std::string& text) {
    this->name(name);
    text_ += jsonString(text);
    return *this;
}

std::string jsonNumber(double number, int digits) {
    if (!std::isfinite(number)) return "null";
    char text[40];
    std::snprintf(text, sizeof text, "%.*g", digits, number);
    return text;
}

JsonLine& JsonLine::field(const std::string& name, double number) {
    this->name(name);
    text_ += jsonNumber(number, 6);  // the events' numbers are times in seconds: 6 digits are plenty
    return *this;
}

JsonLine& JsonLine::field(const std::string& name, uint64_t number) {
    this->name(name);
    text_ += std::to_string(number);
    return *this;
}

JsonLine& JsonLine::field(const std::string& name, int number) {
    this->name(name);
    text_ += std::to_string(number);
    return *this;
}

}  // namespace ddt
