// Canon's maker note as OpenImageIO 2.4 reads and writes it: a TIFF directory inside the EXIF
// block (offsets from the block's TIFF header) whose tags hold values or arrays of numbers,
// each of which OpenImageIO names as an attribute of its own ("Canon:MacroMode", …).
// Numbers and meanings from ExifTool's Canon tag list.
#pragma once

#include <span>

#include "exif_tags.h"

namespace ddt::exif {

// The maker note's tags; those read as arrays (Reading::Indexed) are in canonArrays().
std::span<const Tag> canonTags();

// One array value named by its position.
struct NamedIndex {
    uint16_t index;
    const char* name;
};

// A tag that holds an array of 16-bit numbers, some named.
struct CanonArray {
    uint16_t number;
    FieldType written_as;          // SHORT or SSHORT
    bool is_signed;                // how the numbers are read
    bool minus_one_is_missing;     // CameraSettings: -1 is no value
    std::span<const NamedIndex> names;
};

// The array of that tag number, or null.
const CanonArray* findCanonArray(uint16_t number);
// The arrays OpenImageIO writes, in its order (ShotInfo twice, as it does).
std::span<const CanonArray* const> canonArraysWritten();

}  // namespace ddt::exif
