// The tags of an EXIF block that ddtup names, as OpenImageIO 2.4 names and types them: one table
// for the first TIFF directory, the EXIF directory and the interoperability directory (read
// with the same names), one for the GPS directory. Numbers from TIFF 6.0 and EXIF 2.3.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace ddt::exif {

// TIFF's field types (TIFF 6.0 section 2, plus the IFD type of its supplement).
enum class FieldType : uint16_t {
    None = 0,  // in a table: the tag is known and passed over
    Byte = 1,
    Ascii = 2,
    Short = 3,
    Long = 4,
    Rational = 5,
    SByte = 6,
    Undefined = 7,
    SShort = 8,
    SLong = 9,
    SRational = 10,
    Float = 11,
    Double = 12,
    Ifd = 13,
};

// Bytes of one value of a field type as stored in a block; 0 for None; for a type number
// TIFF does not define, SIZE_MAX (OpenImageIO's -1: its byte counts wrap with it).
size_t fieldTypeBytes(uint16_t type);

// Tags read by a rule of their own instead of by their field type.
enum class Reading : uint8_t {
    ByType,
    FourCharacters,  // a version ("0230"): the 4 bytes as a string, up to a NUL
    FourBytes,       // GPS's version: the 4 bytes as 4 ints
    MakerNote,       // the camera maker's own directory (Canon's only: exif_canon.h)
    Indexed,         // Canon's arrays of numbers, each named (exif_canon.h)
};

struct Tag {
    uint16_t number;
    const char* name;
    FieldType type;  // what a block written by ddtup holds
    uint16_t count;  // values written (rationals); 0: as many as the value has
    Reading reading = Reading::ByType;
};

// The tags of the first, EXIF and interoperability directories, and of the GPS directory.
std::span<const Tag> mainTags();
std::span<const Tag> gpsTags();

// The tag of that number (the later one where two share it), or null.
const Tag* findTag(std::span<const Tag> table, uint16_t number);
// The tag of that name regardless of ASCII case, or null.
const Tag* findTag(std::span<const Tag> table, std::string_view name);

// Tag numbers that point to another directory rather than hold a value.
constexpr uint16_t kExifDirectoryTag = 34665;
constexpr uint16_t kGpsDirectoryTag = 34853;
constexpr uint16_t kInteroperabilityDirectoryTag = 40965;

}  // namespace ddt::exif
