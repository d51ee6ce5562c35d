#include "image_attributes.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <type_traits>

namespace ddt {

double halfValue(uint16_t bits) {
    const int exponent = (bits >> 10) & 0x1F, mantissa = bits & 0x3FF;
    const double sign = bits & 0x8000 ? -1.0 : 1.0;
    if (exponent == 0) return sign * std::ldexp(mantissa, -24);
    if (exponent == 31) return mantissa ? NAN : sign * INFINITY;
    return sign * std::ldexp(mantissa + 1024, exponent - 25);
}

namespace {

using Base = AttributeType::Base;

char lowerAscii(char c) { return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c; }

// The i-th number of `attribute` as a T, converted as C++ converts (integers wrap); its type
// is a number's.
template <class T>
T numberAt(const ImageAttribute& attribute, size_t i) {
    const uint8_t* at = attribute.bytes.data() + i * attribute.type.valueBytes();
    auto get = [at]<class Stored>(Stored) {
        Stored value;
        std::memcpy(&value, at, sizeof value);
        return T(value);
    };
    switch (attribute.type.base) {
        case Base::UInt8: return get(uint8_t());
        case Base::Int8: return get(int8_t());
        case Base::UInt16: return get(uint16_t());
        case Base::Int16: return get(int16_t());
        case Base::UInt32: return get(uint32_t());
        case Base::Int32: return get(int32_t());
        case Base::UInt64: return get(uint64_t());
        case Base::Int64: return get(int64_t());
        case Base::Half: {
            uint16_t bits;
            std::memcpy(&bits, at, sizeof bits);
            return T(halfValue(bits));
        }
        case Base::Float: return get(float());
        case Base::Double: return get(double());
        case Base::String: break;
    }
    return T(0);
}

bool isRational(const AttributeType& type) {
    return type.base == Base::Int32 && type.aggregate == 2 && type.meaning == AttributeType::Meaning::Rational;
}

// The first value as OpenImageIO 2.4's ImageSpec::get_float_attribute and get_int_attribute
// convert it (its convert_type, measured type by type): a single number of any integer type
// to an int; of any type but a 32-bit int (left out there) to a float, and a rational
// divided out; a string that holds only the number, after white space.
template <class T>
bool firstValue(const ImageAttribute* attribute, T& value) {
    if (!attribute || attribute->type.valueCount() == 0) return false;
    const AttributeType& type = attribute->type;
    if (type.base == Base::String) {
        const std::string& text = attribute->strings.front();
        char* end = nullptr;
        if constexpr (std::is_integral_v<T>) value = T(std::strtol(text.c_str(), &end, 10));
        else value = T(std::strtod(text.c_str(), &end));
        return end != text.c_str() && !*end;
    }
    if constexpr (std::is_integral_v<T>) {
        const bool integer = type.base != Base::Half && type.base != Base::Float && type.base != Base::Double;
        if (type.aggregate != 1 || !integer) return false;
    } else {
        if (isRational(type)) {
            const float denominator = numberAt<float>(*attribute, 1);
            value = denominator != 0.0f ? numberAt<float>(*attribute, 0) / denominator : 0.0f;
            return true;
        }
        if (type.aggregate != 1 || type.base == Base::Int32) return false;
    }
    value = numberAt<T>(*attribute, 0);
    return true;
}

ImageAttribute numberAttribute(std::string_view name, Base base, const void* value, size_t size) {
    ImageAttribute attribute{std::string(name), {}, {}, {}};
    attribute.type.base = base;
    attribute.bytes.assign(static_cast<const uint8_t*>(value), static_cast<const uint8_t*>(value) + size);
    return attribute;
}

}  // namespace

size_t AttributeType::valueBytes() const {
    switch (base) {
        case Base::UInt8:
        case Base::Int8: return 1;
        case Base::UInt16:
        case Base::Int16:
        case Base::Half: return 2;
        case Base::UInt32:
        case Base::Int32:
        case Base::Float: return 4;
        case Base::UInt64:
        case Base::Int64:
        case Base::Double: return 8;
        case Base::String: break;
    }
    return 0;
}

bool sameName(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (lowerAscii(a[i]) != lowerAscii(b[i])) return false;
    return true;
}

const ImageAttribute* ImageAttributes::find(std::string_view name) const {
    for (const ImageAttribute& attribute : list_)
        if (sameName(attribute.name, name)) return &attribute;
    return nullptr;
}

void ImageAttributes::set(ImageAttribute attribute) {
    for (ImageAttribute& existing : list_)
        if (sameName(existing.name, attribute.name)) {
            existing = std::move(attribute);
            return;
        }
    list_.push_back(std::move(attribute));
}

void ImageAttributes::set(std::string_view name, int32_t value) { set(numberAttribute(name, Base::Int32, &value, sizeof value)); }

void ImageAttributes::set(std::string_view name, float value) { set(numberAttribute(name, Base::Float, &value, sizeof value)); }

void ImageAttributes::set(std::string_view name, std::string value) {
    ImageAttribute attribute{std::string(name), {}, {}, {std::move(value)}};
    attribute.type.base = Base::String;
    set(std::move(attribute));
}

void ImageAttributes::erase(std::string_view name) {
    std::erase_if(list_, [&](const ImageAttribute& attribute) { return sameName(attribute.name, name); });
}

float ImageAttributes::getFloat(std::string_view name, float fallback) const {
    float value = fallback;
    return firstValue(find(name), value) ? value : fallback;
}

int32_t ImageAttributes::getInt(std::string_view name, int32_t fallback) const {
    int32_t value = fallback;
    return firstValue(find(name), value) ? value : fallback;
}

std::string ImageAttributes::getString(std::string_view name, std::string fallback) const {
    // OpenImageIO looks for a string of that name, passing over others of the same name.
    for (const ImageAttribute& attribute : list_)
        if (sameName(attribute.name, name) && attribute.type.base == Base::String && attribute.type.isScalar())
            return attribute.strings.front();
    return fallback;
}

std::optional<float> ImageAttributes::findFloat(std::string_view name) const {
    for (const ImageAttribute& attribute : list_)
        if (sameName(attribute.name, name) && attribute.type.base == Base::Float && attribute.type.isScalar()) {
            float value;
            std::memcpy(&value, attribute.bytes.data(), sizeof value);
            return value;
        }
    return std::nullopt;
}

}  // namespace ddt
