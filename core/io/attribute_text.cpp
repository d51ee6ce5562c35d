#include "attribute_text.h"

#include <cstdio>
#include <cstring>

namespace ddt {

namespace {

using Base = AttributeType::Base;

template <class... Args>
std::string printed(const char* format, Args... args) {
    char text[64];
    std::snprintf(text, sizeof text, format, args...);
    return text;
}

template <class T>
T valueAt(const ImageAttribute& attribute, size_t index) {
    T value;
    std::memcpy(&value, attribute.bytes.data() + index * sizeof(T), sizeof(T));
    return value;
}

// Backslash, quote and the control characters C writes with a letter, as C escapes them.
std::string escaped(const std::string& text) {
    std::string out;
    for (char c : text) {
        const char* escape = c == '\n' ? "\\n" : c == '\t' ? "\\t" : c == '\v' ? "\\v" : c == '\b' ? "\\b"
                           : c == '\r' ? "\\r" : c == '\f' ? "\\f" : c == '\a' ? "\\a" : c == '\\' ? "\\\\"
                           : c == '"'  ? "\\\"" : nullptr;
        if (escape) out += escape;
        else out += c;
    }
    return out;
}

std::string numberText(const ImageAttribute& attribute, size_t index) {
    switch (attribute.type.base) {
    case Base::UInt8: return printed("%u", unsigned(valueAt<uint8_t>(attribute, index)));
    case Base::Int8: return printed("%d", int(valueAt<int8_t>(attribute, index)));
    case Base::UInt16: return printed("%u", unsigned(valueAt<uint16_t>(attribute, index)));
    case Base::Int16: return printed("%d", int(valueAt<int16_t>(attribute, index)));
    case Base::UInt32: return printed("%u", valueAt<uint32_t>(attribute, index));
    case Base::Int32: return printed("%d", valueAt<int32_t>(attribute, index));
    case Base::UInt64: return printed("%llu", (unsigned long long)valueAt<uint64_t>(attribute, index));
    case Base::Int64: return printed("%lld", (long long)valueAt<int64_t>(attribute, index));
    case Base::Half: return printed("%g", halfValue(valueAt<uint16_t>(attribute, index)));
    case Base::Float: return printed("%g", double(valueAt<float>(attribute, index)));
    case Base::Double: return printed("%g", valueAt<double>(attribute, index));
    case Base::String: break;
    }
    return "";
}

// Two BCD digits from bits [low, low + width) of a SMPTE timecode word.
int bcdField(uint32_t word, int low, int width) {
    const uint32_t bits = (word >> low) & ((1u << width) - 1);
    return int((bits & 0x0f) + 10 * ((bits >> 4) & 0x0f));
}

}  // namespace

std::string attributeText(const ImageAttribute& attribute) {
    const AttributeType& type = attribute.type;
    const size_t elements = type.array_length ? type.array_length : 1;
    if (type.base == Base::String) {
        // Each string up to a NUL it may hold, as OpenImageIO reads its C strings.
        if (type.array_length == 0 && type.aggregate == 1) return attribute.strings.empty() ? "" : attribute.strings[0].c_str();
        std::string out;
        for (size_t i = 0; i < attribute.strings.size(); ++i)
            out += (i ? ", \"" : "\"") + escaped(attribute.strings[i].c_str()) + "\"";
        return out;
    }
    const bool rational = type.meaning == AttributeType::Meaning::Rational && type.aggregate == 2;
    if (rational && (type.base == Base::Int32 || type.base == Base::UInt32)) {
        std::string out;
        for (size_t i = 0; i < elements; ++i) {
            out += i ? ", " : "";
            out += numberText(attribute, 2 * i) + "/" + numberText(attribute, 2 * i + 1);
        }
        return out;
    }
    // A SMPTE timecode: two words, the first its BCD time.
    if (type.base == Base::UInt32 && type.meaning == AttributeType::Meaning::Timecode && type.aggregate == 1 &&
        type.array_length == 2) {
        const uint32_t word = valueAt<uint32_t>(attribute, 0);
        return printed("%02d:%02d:%02d:%02d", bcdField(word, 24, 6), bcdField(word, 16, 7), bcdField(word, 8, 7),
                       bcdField(word, 0, 6));
    }
    std::string out;
    for (size_t i = 0; i < type.valueCount(); ++i) out += (i ? ", " : "") + numberText(attribute, i);
    return out;
}

}  // namespace ddt
