// One JSON object on one line, built field by field: the --progress=json events.
#pragma once

#include <cstdint>
#include <string>

namespace ddt {

class JsonLine {
public:
    JsonLine& field(const std::string& name, const std::string& text);
    JsonLine& field(const std::string& name, const char* text) { return field(name, std::string(text)); }
    JsonLine& field(const std::string& name, double number);  // non-finite numbers become null
    JsonLine& field(const std::string& name, uint64_t number);
    JsonLine& field(const std::string& name, int number);
    // The object with its closing brace and a newline.
    std::string text() const { return (text_.empty() ? "{" : text_) + "}\n"; }

private:
    void name(const std::string& name);
    std::string text_;
};

// `text` as a JSON string literal, quotes included. Bytes that are not valid UTF-8 (file names
// may hold any) become U+FFFD, so every line stays valid JSON.
std::string jsonString(const std::string& text);
// `number` with `digits` significant digits; null for NaN and the infinities, which JSON lacks.
std::string jsonNumber(double number, int digits);

}  // namespace ddt
