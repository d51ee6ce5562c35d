// Writing attributes as a little-endian EXIF block (exif.h), byte for byte as OpenImageIO 2.4's
// encode_exif writes it: the TIFF header; the values longer than 4 bytes, in the attributes'
// order, then Canon's maker note's; the first directory (its entries in the attributes' order,
// then the pointers to the EXIF and GPS directories); the EXIF directory; the GPS directory;
// the maker note's directory (these three sorted by tag).
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>

#include "exif.h"
#include "exif_canon.h"
#include "exif_tags.h"

namespace ddt {

namespace {

using exif::FieldType;
using exif::Tag;
using Base = AttributeType::Base;

// EXIF tags from ExposureTime to ImageUniqueID go in the EXIF directory, all others in the
// first (OpenImageIO's range: the EXIF 2.3 tags after ImageUniqueID land in the first too).
constexpr uint16_t kFirstExifDirectoryTag = 33434, kLastExifDirectoryTag = 42016;
constexpr uint16_t kMakerNoteTag = 37500;

struct Entry {
    uint16_t tag;
    FieldType type;
    uint32_t count;
    uint8_t field[4];  // the value where it fits, else its offset
};

void append16(std::string& out, uint16_t value) { out.append({char(value & 0xFF), char(value >> 8)}); }
void append32(std::string& out, uint32_t value) {
    append16(out, uint16_t(value & 0xFFFF));
    append16(out, uint16_t(value >> 16));
}

// A directory's entries, and the block whose end holds the values longer than 4 bytes.
class Directory {
public:
    explicit Directory(std::string& block) : block_(block) {}
    const std::vector<Entry>& entries() const { return entries_; }
    bool empty() const { return entries_.empty(); }
    size_t bytes() const { return 2 + entries_.size() * 12 + 4; }  // count, entries, next directory

    // Adds an entry with its little-endian value; one of the same tag is replaced where it stands
    // (its value, if in the block, stays there unused).
    void add(uint16_t tag, FieldType type, uint32_t count, const std::string& value) {
        if (value.size() <= 4) {
            Entry entry{tag, type, count, {}};
            std::memcpy(entry.field, value.data(), value.size());
            return put(entry);
        }
        addAt(tag, type, count, block_.size());
        block_ += value;
    }
    // Adds an entry whose value is at `offset` in the block.
    void addAt(uint16_t tag, FieldType type, uint32_t count, size_t offset) {
        Entry entry{tag, type, count, {}};
        std::string bytes;
        append32(bytes, uint32_t(offset));
        std::memcpy(entry.field, bytes.data(), 4);
        put(entry);
    }
    bool has(uint16_t tag) const {
        return std::any_of(entries_.begin(), entries_.end(), [&](const Entry& entry) { return entry.tag == tag; });
    }

    void sortByTag() {
        std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) { return a.tag < b.tag; });
    }

    void write() const {
        append16(block_, uint16_t(entries_.size()));
        for (const Entry& entry : entries_) {
            append16(block_, entry.tag);
            append16(block_, uint16_t(entry.type));
            append32(block_, entry.count);
            block_.append(reinterpret_cast<const char*>(entry.field), 4);
        }
        append32(block_, 0);  // no next directory
    }

private:
    void put(const Entry& entry) {
        for (Entry& existing : entries_)
            if (existing.tag == entry.tag) {
                existing = entry;
                return;
            }
        entries_.push_back(entry);
    }

    std::string& block_;
    std::vector<Entry> entries_;
};

// A float converted to int as x86 converts it: INT_MIN where it does not fit (or is NaN).
int32_t truncated(double value) {
    return value > -2147483649.0 && value < 2147483648.0 ? int32_t(value) : INT32_MIN;
}

// OpenImageIO's float_to_rational: an exact inverse as 1/n (of which 0.5 gives 1/0, kept as
// it is), else decimals until within 1e-5 or a denominator of 10^6.
void unsignedRational(float f, uint32_t& numerator, uint32_t& denominator) {
    if (f <= 0) {
        numerator = 0, denominator = 1;
        return;
    }
    const double inverse = 1.0 / f;
    if (truncated(inverse) == inverse) {
        numerator = 1, denominator = uint32_t(truncated(f));
        return;
    }
    numerator = uint32_t(truncated(f)), denominator = 1;
    while (std::fabs(f - float(numerator)) > 0.00001f && denominator < 1000000) {
        denominator *= 10;
        f *= 10;
        numerator = uint32_t(truncated(f));
    }
}

void signedRational(float f, int32_t& numerator, int32_t& denominator) {
    uint32_t n, d;
    unsignedRational(std::fabs(f), n, d);
    numerator = f >= 0 ? int32_t(n) : int32_t(0u - n);
    denominator = int32_t(d);
}

// The first number of an attribute of 32- or 16-bit integers (OpenImageIO converts no others).
bool firstInteger(const ImageAttribute& attribute, int64_t& value) {
    const uint8_t* bytes = attribute.bytes.data();
    if (attribute.bytes.empty()) return false;
    switch (attribute.type.base) {
        case Base::UInt32: { uint32_t v; std::memcpy(&v, bytes, 4); value = v; return true; }
        case Base::Int32: { int32_t v; std::memcpy(&v, bytes, 4); value = v; return true; }
        case Base::UInt16: { uint16_t v; std::memcpy(&v, bytes, 2); value = v; return true; }
        case Base::Int16: { int16_t v; std::memcpy(&v, bytes, 2); value = v; return true; }
        default: return false;
    }
}

// The value of `attribute` as the tag's type, where OpenImageIO writes one: a single string as
// ASCII; floats as the tag's count of rationals; the first integer as one SHORT, LONG or BYTE.
void addAttribute(const ImageAttribute& attribute, const Tag& tag, Directory& directory) {
    const AttributeType& type = attribute.type;
    std::string value;
    switch (tag.type) {
        case FieldType::Ascii: {
            // Up to a NUL, as OpenImageIO's spec holds a string; with a NUL after it.
            if (type.base != Base::String || !type.isScalar()) return;
            const std::string text = attribute.strings.front().c_str();
            if (text.empty()) return;
            value.assign(text.c_str(), text.size() + 1);
            return directory.add(tag.number, tag.type, uint32_t(value.size()), value);
        }
        case FieldType::Rational:
        case FieldType::SRational: {
            if (type.base != Base::Float || type.aggregate != 1) return;
            // OpenImageIO reads the tag's count whatever the attribute holds; missing ones are 0 here.
            for (size_t i = 0; i < tag.count; ++i) {
                float f = 0;
                if (i < type.valueCount()) std::memcpy(&f, attribute.bytes.data() + 4 * i, 4);
                uint32_t numerator, denominator;
                if (tag.type == FieldType::Rational) {
                    unsignedRational(f, numerator, denominator);
                } else {
                    int32_t n, d;
                    signedRational(f, n, d);
                    numerator = uint32_t(n), denominator = uint32_t(d);
                }
                append32(value, numerator);
                append32(value, denominator);
            }
            return directory.add(tag.number, tag.type, tag.count, value);
        }
        case FieldType::Short:
        case FieldType::Long:
        case FieldType::Byte: {
            int64_t number;
            if (!firstInteger(attribute, number)) return;
            if (tag.type == FieldType::Byte) value.push_back(char(uint8_t(number)));
            else if (tag.type == FieldType::Short) append16(value, uint16_t(number));
            else append32(value, uint32_t(number));
            return directory.add(tag.number, tag.type, 1, value);
        }
        default:
            return;  // UNDEFINED and passed-over tags: OpenImageIO writes none from attributes
    }
}

// Canon's maker note from "Canon:" attributes, as OpenImageIO writes it: each tag of a value
// whose attribute is there, its bytes as they are in the attribute (a string's up to a NUL,
// with one after it); then the arrays of which any named value is there, the others 0.
void addCanonMakerNote(const ImageAttributes& attributes, Directory& directory) {
    for (const Tag& tag : exif::canonTags()) {
        const ImageAttribute* attribute = tag.reading == exif::Reading::ByType ? attributes.find(tag.name) : nullptr;
        if (!attribute) continue;
        const bool is_string = attribute->type.base == Base::String;
        if (tag.type == FieldType::Ascii) {
            // OpenImageIO writes a number's text here; ddtup reads none such, so writes none.
            if (!is_string) continue;
            const std::string text = attribute->strings.front().c_str();
            directory.add(tag.number, tag.type, uint32_t(text.size() + 1), std::string(text.c_str(), text.size() + 1));
        } else if (!is_string) {
            // The tag's count of values, whatever the attribute holds: missing bytes are 0 here
            // (OpenImageIO reads past the value).
            std::string value(exif::fieldTypeBytes(uint16_t(tag.type)) * tag.count, '\0');
            std::memcpy(value.data(), attribute->bytes.data(), std::min(value.size(), attribute->bytes.size()));
            directory.add(tag.number, tag.type, tag.count, value);
        }
    }
    for (const exif::CanonArray* array : exif::canonArraysWritten()) {
        std::vector<uint16_t> values(array->names.back().index + 1u, 0);
        bool any = false;
        for (const exif::NamedIndex& named : array->names)
            if (attributes.find(named.name)) {
                values[named.index] = uint16_t(attributes.getInt(named.name));
                any = true;
            }
        if (!any) continue;
        std::string bytes;
        for (uint16_t value : values) append16(bytes, value);
        directory.add(array->number, array->written_as, uint32_t(values.size()), bytes);
    }
}

bool startsWith(std::string_view name, std::string_view prefix, bool ignore_case) {
    if (name.size() < prefix.size()) return false;
    return ignore_case ? sameName(name.substr(0, prefix.size()), prefix) : name.substr(0, prefix.size()) == prefix;
}

}  // namespace

std::string encodeExif(const ImageAttributes& attributes) {
    const bool any = std::any_of(attributes.all().begin(), attributes.all().end(), [](const ImageAttribute& a) {
        return startsWith(a.name, "Exif:", true) || startsWith(a.name, "GPS:", true);
    });
    if (!any) return "";

    std::string block = "II";
    append16(block, 42);
    append32(block, 0);  // the first directory's offset, known at the end
    Directory first_directory(block), exif_directory(block), gps_directory(block);

    for (const ImageAttribute& attribute : attributes.all()) {
        if (startsWith(attribute.name, "GPS:", false)) {
            if (const Tag* tag = exif::findTag(exif::gpsTags(), attribute.name))
                addAttribute(attribute, *exif::findTag(exif::gpsTags(), tag->number), gps_directory);
        } else if (const Tag* tag = exif::findTag(exif::mainTags(), attribute.name)) {
            const bool in_exif = tag->number >= kFirstExifDirectoryTag && tag->number <= kLastExifDirectoryTag;
            // The tag's type is that of the later tag of its number (ISOSpeedRatings').
            addAttribute(attribute, *exif::findTag(exif::mainTags(), tag->number), in_exif ? exif_directory : first_directory);
        }
    }

    Directory maker_directory(block);
    if (sameName(attributes.getString("Make"), "Canon")) addCanonMakerNote(attributes, maker_directory);

    // The versions EXIF and GPS directories must hold (EXIF 2.3, FlashPix 1.0, GPS 2.2), and
    // the order of the YCbCr components.
    if (!exif_directory.empty() || !maker_directory.empty()) {
        exif_directory.add(36864, FieldType::Undefined, 4, "0230");
        exif_directory.add(40960, FieldType::Undefined, 4, "0100");
        exif_directory.add(37121, FieldType::Undefined, 4, std::string("\1\2\3\0", 4));
    }
    if (!gps_directory.empty()) gps_directory.add(0, FieldType::Byte, 4, std::string("\2\2\0\0", 4));

    const size_t first_offset = block.size();
    const size_t first_bytes = first_directory.bytes() + 12 * (!exif_directory.empty() + !gps_directory.empty());
    const size_t exif_offset = first_offset + first_bytes;
    // The EXIF directory's size counts the maker note's entry to come, unless it replaces one of
    // an attribute ("Exif:MakerNote"): OpenImageIO counts it again there, and stops on an assertion.
    const bool maker_note_entry = !maker_directory.empty() && !exif_directory.has(kMakerNoteTag);
    const size_t exif_bytes = exif_directory.empty() ? 0 : exif_directory.bytes() + 12 * maker_note_entry;
    const size_t gps_offset = exif_offset + exif_bytes;
    const size_t maker_offset = gps_offset + (gps_directory.empty() ? 0 : gps_directory.bytes());
    if (!maker_directory.empty())
        exif_directory.addAt(kMakerNoteTag, FieldType::Byte, uint32_t(maker_directory.bytes()), maker_offset);
    std::string pointer;
    if (!exif_directory.empty()) {
        append32(pointer, uint32_t(exif_offset));
        first_directory.add(exif::kExifDirectoryTag, FieldType::Long, 1, pointer);
    }
    if (!gps_directory.empty()) {
        pointer.clear();
        append32(pointer, uint32_t(gps_offset));
        first_directory.add(exif::kGpsDirectoryTag, FieldType::Long, 1, pointer);
    }
    exif_directory.sortByTag();
    gps_directory.sortByTag();
    maker_directory.sortByTag();

    first_directory.write();
    if (!exif_directory.empty()) exif_directory.write();
    if (!gps_directory.empty()) gps_directory.write();
    if (!maker_directory.empty()) maker_directory.write();
    pointer.clear();
    append32(pointer, uint32_t(first_offset));
    block.replace(4, 4, pointer);
    return block;
}

}  // namespace ddt
