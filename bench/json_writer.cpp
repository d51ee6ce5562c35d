#include "json_writer.h"

#include <cassert>
#include <cmath>
#include <cstdio>

namespace bench {

namespace {

std::string quoted(const std::string& text) {
    std::string out = "\"";
    for (unsigned char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += char(c);
        } else if (c < 0x20) {
            char escape[8];
            std::snprintf(escape, sizeof escape, "\\u%04x", c);
            out += escape;
        } else {
            out += char(c);
        }
    }
    return out + "\"";
}

}  // namespace

void JsonWriter::newLine() {
    text_ += '\n';
    text_.append(2 * has_items_.size(), ' ');
}

void JsonWriter::startValue() {
    if (after_key_) {
        after_key_ = false;
        return;
    }
    if (has_items_.empty()) return;
    if (has_items_.back()) text_ += ",";
    has_items_.back() = true;
    newLine();
}

JsonWriter& JsonWriter::open(char bracket) {
    startValue();
    text_ += bracket;
    has_items_.push_back(false);
    return *this;
}

JsonWriter& JsonWriter::close(char bracket) {
    assert(!has_items_.empty() && !after_key_);
    const bool had_items = has_items_.back();
    has_items_.pop_back();
    if (had_items) newLine();
    text_ += bracket;
    return *this;
}

JsonWriter& JsonWriter::beginObject() { return open('{'); }
JsonWriter& JsonWriter::endObject() { return close('}'); }
JsonWriter& JsonWriter::beginArray() { return open('['); }
JsonWriter& JsonWriter::endArray() { return close(']'); }

JsonWriter& JsonWriter::key(const std::string& name) {
    startValue();
    text_ += quoted(name) + ": ";
    after_key_ = true;
    return *this;
}

JsonWriter& JsonWriter::value(const std::string& text) {
    startValue();
    text_ += quoted(text);
    return *this;
}

JsonWriter& JsonWriter::value(double number) {
    startValue();
    if (!std::isfinite(number)) {
        text_ += "null";
        return *this;
    }
    // 12 significant digits: far beyond what any measurement here resolves.
    char text[32];
    std::snprintf(text, sizeof text, "%.12g", number);
    text_ += text;
    return *this;
}

JsonWriter& JsonWriter::value(uint64_t number) {
    startValue();
    text_ += std::to_string(number);
    return *this;
}

JsonWriter& JsonWriter::value(bool flag) {
    startValue();
    text_ += flag ? "true" : "false";
    return *this;
}

}  // namespace bench
