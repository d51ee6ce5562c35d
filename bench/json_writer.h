// A small streaming JSON writer for the raw measurements: objects, arrays, strings and
// numbers, indented. Non-finite numbers (an infinite PSNR, an undefined correlation) have
// no JSON form and are written as null.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

class JsonWriter {
public:
    JsonWriter& beginObject();
    JsonWriter& endObject();
    JsonWriter& beginArray();
    JsonWriter& endArray();
    JsonWriter& key(const std::string& name);  // inside an object, before each value
    JsonWriter& value(const std::string& text);
    JsonWriter& value(const char* text) { return value(std::string(text)); }
    JsonWriter& value(double number);
    JsonWriter& value(uint64_t number);
    JsonWriter& value(uint32_t number) { return value(uint64_t(number)); }
    JsonWriter& value(bool flag);

    // The document; complete once every container is closed.
    const std::string& text() const { return text_; }

private:
    void startValue();
    void newLine();  // and indent to the depth of the open containers
    JsonWriter& open(char bracket);
    JsonWriter& close(char bracket);

    std::string text_;
    std::vector<bool> has_items_;  // per open container
    bool after_key_ = false;
};

}  // namespace bench
