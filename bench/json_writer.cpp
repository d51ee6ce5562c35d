#include "json_writer.h"

#include <cassert>

#include "json_line.h"

namespace bench {

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
    text_ += ddt::jsonString(name) + ": ";
    after_key_ = true;
    return *this;
}

JsonWriter& JsonWriter::value(const std::string& text) {
    startValue();
    text_ += ddt::jsonString(text);
    return *this;
}

JsonWriter& JsonWriter::value(double number) {
    startValue();
    text_ += ddt::jsonNumber(number, 12);  // far beyond what any measurement here resolves
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
