// An image file's attributes (resolution, colour space, ICC profile, EXIF, text, …) as ddtup
// holds them: a list of typed name/value pairs, read and written by OpenImageIO's rules.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ddt {

// The type of an attribute's values: numbers of one kind, or strings, grouped in elements (a
// vector, a matrix), one element or an array of them; OpenImageIO's TypeDesc says the same.
struct AttributeType {
    enum class Base : uint8_t { UInt8, Int8, UInt16, Int16, UInt32, Int32, UInt64, Int64, Half, Float, Double, String };
    // What an element of several values is, where a format says.
    enum class Meaning : uint8_t { None, Colour, Point, Vector, Normal, Timecode, Keycode, Rational, Box };

    Base base = Base::Int32;
    uint8_t aggregate = 1;  // values per element: 1, 2, 3, 4, 9 (3×3 matrix) or 16 (4×4)
    Meaning meaning = Meaning::None;
    uint32_t array_length = 0;  // elements of an array; 0: one element, not an array

    size_t valueCount() const { return size_t(aggregate) * (array_length ? array_length : 1); }
    size_t valueBytes() const;  // of one number; 0 for strings
    bool isScalar() const { return aggregate == 1 && array_length == 0; }
    bool operator==(const AttributeType&) const = default;
};

// One attribute, named as OpenImageIO names it ("XResolution", "Exif:FNumber", "ICCProfile").
struct ImageAttribute {
    std::string name;
    AttributeType type;
    std::vector<uint8_t> bytes;        // the numbers, valueCount() of them, in the machine's byte order
    std::vector<std::string> strings;  // the strings, valueCount() of them, when type.base is String
};

// The attributes of an image in the file's order. Names are matched regardless of (ASCII)
// case, and values converted, as OpenImageIO's ImageSpec matches and converts them, so that
// what is made of them (png_metadata.h) is what OpenImageIO made of the same attributes.
class ImageAttributes {
public:
    const std::vector<ImageAttribute>& all() const { return list_; }
    bool empty() const { return list_.empty(); }

    // The first attribute of that name, or null.
    const ImageAttribute* find(std::string_view name) const;
    // Appends an attribute, whatever its name.
    void append(ImageAttribute attribute) { list_.push_back(std::move(attribute)); }
    // Replaces the first attribute of that name where it stands, else appends it.
    void set(ImageAttribute attribute);
    void set(std::string_view name, int32_t value);
    void set(std::string_view name, float value);
    void set(std::string_view name, std::string value);
    // Removes every attribute of that name.
    void erase(std::string_view name);

    // The first value of a number or of a string that holds only one, converted as OpenImageIO
    // 2.4 converts (image_attributes.cpp says how); `fallback` for anything else or nothing.
    float getFloat(std::string_view name, float fallback = 0.0f) const;
    int32_t getInt(std::string_view name, int32_t fallback = 0) const;
    // A single string's value; `fallback` if the attribute is no single string.
    std::string getString(std::string_view name, std::string fallback = "") const;
    // A single float's value (no conversion), if there is one of that name.
    std::optional<float> findFloat(std::string_view name) const;

private:
    std::vector<ImageAttribute> list_;
};

// The value of an IEEE binary16 number (OpenEXR's half) of these bits.
double halfValue(uint16_t bits);

// Whether two names are equal regardless of ASCII case.
bool sameName(std::string_view a, std::string_view b);

}  // namespace ddt
