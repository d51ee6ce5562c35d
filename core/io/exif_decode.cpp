// Reading an EXIF block's directories into attributes (exif.h). The rules, each OpenImageIO
// 2.4's: only the first directory and those its tags point to are read (not the thumbnail's);
// a directory entry must end before the block's last byte; a value of up to 4 bytes sits in
// the entry itself; a pointer seen before, or beyond the block, is not followed; SHORT and
// LONG values keep their type, rationals become floats, strings lose their trailing NULs and
// end at the first NUL, one BYTE becomes an int; other types are passed over.
#include <algorithm>
#include <cstring>
#include <set>
#include <utility>

#include "exif.h"
#include "exif_canon.h"
#include "exif_tags.h"

namespace ddt {

namespace {

using exif::FieldType;
using exif::Tag;

constexpr size_t kEntryBytes = 12;  // tag, type, count, value or offset
// Where the maker note is, noted while reading and dropped at the end (decodeExif).
constexpr const char* kMakerNoteOffset = "oiio:MakerNoteOffset";
constexpr int kMaxMakerNoteDepth = 4;

class Block {
public:
    Block(const uint8_t* data, size_t size, bool big_endian) : data_(data), size_(size), big_endian_(big_endian) {}
    size_t size() const { return size_; }
    const uint8_t* at(size_t offset) const { return data_ + offset; }

    uint16_t u16(const uint8_t* p) const { return big_endian_ ? uint16_t(p[0] << 8 | p[1]) : uint16_t(p[1] << 8 | p[0]); }
    uint32_t u32(const uint8_t* p) const {
        return big_endian_ ? uint32_t(u16(p)) << 16 | u16(p + 2) : uint32_t(u16(p + 2)) << 16 | u16(p);
    }

private:
    const uint8_t* data_;
    size_t size_;
    bool big_endian_;
};

struct Entry {
    uint16_t tag;
    uint16_t type;
    uint32_t count;
    uint32_t offset;   // the last field read as a number: where a longer value starts
    uint8_t field[4];  // the same field's bytes: a value of up to 4 bytes
    const Block* block;

    // The value's bytes, wrapping as OpenImageIO's size_t does for types TIFF does not define.
    size_t bytes() const { return exif::fieldTypeBytes(type) * count; }
    // Where the value is, or null where it does not lie inside the block. An offset read as
    // negative (OpenImageIO holds it in an int) lies outside.
    const uint8_t* value() const {
        const size_t length = bytes();
        if (length <= 4) return field;
        if (int32_t(offset) < 0 || offset + length > block->size()) return nullptr;
        return block->at(offset);
    }
};

ImageAttribute numbers(const char* name, AttributeType::Base base, uint32_t count, const void* values, size_t value_bytes) {
    ImageAttribute attribute{name, {}, {}, {}};
    attribute.type.base = base;
    // One value is a scalar; so is none, read as a zero.
    attribute.type.array_length = count > 1 ? count : 0;
    attribute.bytes.assign(attribute.type.valueCount() * value_bytes, 0);
    if (count) std::memcpy(attribute.bytes.data(), values, count * value_bytes);
    return attribute;
}

class Decoder {
public:
    Decoder(const Block& block, ImageAttributes& attributes) : block_(block), attributes_(attributes) {}

    // Canon's maker note, read last with the sub-directories seen so far.
    bool readMakerNoteAtEnd(uint32_t offset) {
        ++maker_note_depth_;
        return readDirectory(offset, exif::canonTags());
    }

    // Reads the directory at `offset`; false where its entries do not fit in the block.
    bool readDirectory(size_t offset, std::span<const Tag> table) {
        if (offset + 2 > block_.size()) return false;
        const uint16_t entries = block_.u16(block_.at(offset));
        if (offset + 2 + entries * kEntryBytes > block_.size()) return false;
        for (size_t i = 0; i < entries; ++i) readEntry(offset + 2 + i * kEntryBytes, table);
        return true;
    }

private:
    void readEntry(size_t position, std::span<const Tag> table) {
        // Ending at the block's last byte already counts as outside (OpenImageIO's test).
        if (position + kEntryBytes >= block_.size()) return;
        const uint8_t* p = block_.at(position);
        Entry entry{block_.u16(p), block_.u16(p + 2), block_.u32(p + 4), block_.u32(p + 8), {}, &block_};
        std::memcpy(entry.field, p + 8, 4);

        if (entry.tag == exif::kExifDirectoryTag) return readSubdirectory(entry.offset, exif::mainTags(), false);
        if (entry.tag == exif::kGpsDirectoryTag) return readSubdirectory(entry.offset, exif::gpsTags(), true);
        if (entry.tag == exif::kInteroperabilityDirectoryTag) return readSubdirectory(entry.offset, exif::mainTags(), false);

        const Tag* tag = exif::findTag(table, entry.tag);
        if (!tag || has(tag->name)) return;
        switch (tag->reading) {
            case exif::Reading::ByType:
                if (tag->type != FieldType::None) addValue(tag->name, entry);
                break;
            case exif::Reading::FourCharacters:
                // Up to a NUL, as OpenImageIO's string attributes hold it.
                if (entry.bytes() == 4) {
                    const char* text = reinterpret_cast<const char*>(entry.field);
                    attributes_.set(tag->name, std::string(text, strnlen(text, 4)));
                }
                break;
            case exif::Reading::FourBytes:
                if (entry.bytes() == 4) {
                    const int32_t values[4] = {entry.field[0], entry.field[1], entry.field[2], entry.field[3]};
                    attributes_.set(numbers(tag->name, AttributeType::Base::Int32, 4, values, 4));
                }
                break;
            case exif::Reading::MakerNote:
                if (entry.bytes() > 4) readMakerNote(entry.offset);
                break;
            case exif::Reading::Indexed:
                addArray(*exif::findCanonArray(entry.tag), entry);
                break;
        }
    }

    // Canon's maker note is read at once where the make is already known, with sub-directories
    // seen before read again (OpenImageIO's fresh list); any other's offset is noted for the
    // end (decodeExif), when the make surely is known. A maker note that leads to itself would
    // take OpenImageIO round until its stack overflowed: ddtup stops at a depth no camera has.
    void readMakerNote(uint32_t offset) {
        if (attributes_.getString("Make") != "Canon") {
            attributes_.set(kMakerNoteOffset, int32_t(offset));
            return;
        }
        if (maker_note_depth_ == kMaxMakerNoteDepth) return;
        ++maker_note_depth_;
        std::set<uint32_t> outer = std::exchange(seen_, {});
        readDirectory(offset, exif::canonTags());
        seen_ = std::move(outer);
        --maker_note_depth_;
    }

    // Canon's arrays of SHORT or SSHORT: each named position present, as an int.
    void addArray(const exif::CanonArray& array, const Entry& entry) {
        if (entry.type != uint16_t(FieldType::Short) && entry.type != uint16_t(FieldType::SShort)) return;
        const uint8_t* values = entry.value();
        if (!values) return;
        for (const exif::NamedIndex& named : array.names) {
            if (named.index >= entry.count) continue;
            const uint16_t bits = block_.u16(values + 2 * named.index);
            const int32_t value = array.is_signed ? int32_t(int16_t(bits)) : int32_t(bits);
            if (array.minus_one_is_missing && value == -1) continue;
            attributes_.set(named.name, value);
        }
    }

    void readSubdirectory(uint32_t offset, std::span<const Tag> table, bool gps) {
        if (offset >= block_.size() || !seen_.insert(offset).second) return;
        // With no room for the count there is no room for an entry either.
        if (size_t(offset) + 2 > block_.size()) return;
        const uint16_t entries = block_.u16(block_.at(offset));
        // GPS has 32 tags: more is a count of the wrong byte order, seen in broken files.
        if (gps && entries > 32) return;
        for (size_t i = 0; i < entries; ++i) readEntry(offset + 2 + i * kEntryBytes, table);
    }

    // An attribute of exactly that name (OpenImageIO's test before reading a tag).
    bool has(std::string_view name) const {
        for (const ImageAttribute& attribute : attributes_.all())
            if (attribute.name == name) return true;
        return false;
    }

    void addValue(const char* name, const Entry& entry) {
        const uint8_t* value = entry.value();
        if (!value) return;
        using Base = AttributeType::Base;
        switch (FieldType(entry.type)) {
            case FieldType::Short: {
                std::vector<uint16_t> shorts(entry.count);
                for (uint32_t i = 0; i < entry.count; ++i) shorts[i] = block_.u16(value + 2 * i);
                attributes_.set(numbers(name, Base::UInt16, entry.count, shorts.data(), 2));
                break;
            }
            case FieldType::Long: {
                std::vector<uint32_t> longs(entry.count);
                for (uint32_t i = 0; i < entry.count; ++i) longs[i] = block_.u32(value + 4 * i);
                attributes_.set(numbers(name, Base::UInt32, entry.count, longs.data(), 4));
                break;
            }
            case FieldType::Rational:
            case FieldType::SRational: {
                const bool is_signed = entry.type == uint16_t(FieldType::SRational);
                std::vector<float> quotients(entry.count);
                for (uint32_t i = 0; i < entry.count; ++i) {
                    const uint32_t numerator = block_.u32(value + 8 * i), denominator = block_.u32(value + 8 * i + 4);
                    quotients[i] = is_signed ? float(double(int32_t(numerator)) / double(int32_t(denominator)))
                                             : float(double(numerator) / double(denominator));
                }
                attributes_.set(numbers(name, Base::Float, entry.count, quotients.data(), 4));
                break;
            }
            case FieldType::Ascii: {
                size_t length = entry.count;
                while (length && value[length - 1] == 0) --length;
                std::string text(reinterpret_cast<const char*>(value), length);
                attributes_.set(name, std::string(text.c_str()));
                break;
            }
            case FieldType::Byte:
                if (entry.count == 1) attributes_.set(name, int32_t(value[0]));
                break;
            default:
                break;  // signed integers, floats, UNDEFINED and BYTE arrays: OpenImageIO keeps none
        }
    }

    const Block& block_;
    ImageAttributes& attributes_;
    std::set<uint32_t> seen_;  // sub-directories read, so that a loop of pointers ends
    int maker_note_depth_ = 0;  // maker notes being read, one inside another
};

// OpenImageIO's reading of EXIF's colour space: any value but 0xFFFF (uncalibrated) is sRGB.
void noteColourSpace(ImageAttributes& attributes) {
    const ImageAttribute* space = attributes.find("Exif:ColorSpace");
    if (!space) space = attributes.find("ColorSpace");
    if (!space) return;
    int32_t value = -1;
    const AttributeType& type = space->type;
    using Base = AttributeType::Base;
    if (type.isScalar() && (type.base == Base::UInt32 || type.base == Base::Int32)) {
        std::memcpy(&value, space->bytes.data(), 4);
    } else if (type.isScalar() && (type.base == Base::UInt16 || type.base == Base::Int16)) {
        uint16_t bits;
        std::memcpy(&bits, space->bytes.data(), 2);
        value = type.base == Base::UInt16 ? int32_t(bits) : int32_t(int16_t(bits));
    }
    if (value != 0xFFFF) attributes.set("oiio:ColorSpace", std::string("sRGB"));
}

}  // namespace

bool decodeExif(const uint8_t* data, size_t size, ImageAttributes& attributes) {
    if (size >= 6 && std::memcmp(data, "Exif\0\0", 6) == 0) {
        data += 6;
        size -= 6;
    }
    // The TIFF header: byte order, 42 (not checked), the first directory's offset.
    if (size < 8) return false;
    const bool big_endian = data[0] == 'M' && data[1] == 'M';
    if (!big_endian && !(data[0] == 'I' && data[1] == 'I')) return false;
    const Block block(data, size, big_endian);
    Decoder decoder(block, attributes);
    if (!decoder.readDirectory(block.u32(data + 4), exif::mainTags())) return false;

    noteColourSpace(attributes);
    // A maker note met before the make: read now if Canon's (any case here). The note of where
    // it is goes, but only when above 0, as OpenImageIO leaves it.
    const int32_t maker_note = attributes.getInt(kMakerNoteOffset);
    if (maker_note > 0) {
        if (sameName(attributes.getString("Make"), "Canon") && !decoder.readMakerNoteAtEnd(uint32_t(maker_note))) return false;
        attributes.erase(kMakerNoteOffset);
    }
    return true;
}

}  // namespace ddt
