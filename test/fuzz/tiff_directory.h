// TIFF's image file directories (IFDs), as TIFF files and EXIF blocks hold them: reading
// their entries and damaging one. Classic TIFF and BigTIFF, either byte order.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "random.h"

namespace fuzz {

struct TiffEntry {
    size_t at;  // offset of the entry (12 bytes, BigTIFF's 20) in the bytes
    uint16_t tag, type;
    uint64_t count;
    uint64_t value;  // the value field: the value itself when it fits in it, else an offset
};

struct TiffLayout {
    bool little_endian = true;
    bool big = false;                 // BigTIFF: 8-byte counts, offsets and value fields
    std::vector<size_t> directories;  // offsets of the IFDs found, sub-IFDs (EXIF, GPS) included
    std::vector<TiffEntry> entries;   // of all of them

    uint64_t get(const std::string& bytes, size_t at, int size) const;
    void put(std::string& bytes, size_t at, int size, uint64_t value) const;
    const TiffEntry* find(uint16_t tag) const;
    // Field sizes and places, which BigTIFF widens: an entry's count and value fields, an
    // IFD's entry count, the links to IFDs.
    int offsetSize() const { return big ? 8 : 4; }
    int entryCountSize() const { return big ? 8 : 2; }
    size_t entrySize() const { return big ? 20 : 12; }
    size_t countAt(const TiffEntry& entry) const { return entry.at + 4; }
    size_t valueAt(const TiffEntry& entry) const { return entry.at + (big ? 12 : 8); }
    size_t firstLinkAt() const { return big ? 8 : 4; }
    size_t nextLinkAt(const std::string& bytes, size_t directory) const;
    // Where an entry's values are (inline or at its offset) and how many bytes each takes.
    size_t valuesAt(const TiffEntry& entry) const;
    static int typeSize(uint16_t type);
    // The entry's values as integers (SHORT, LONG, BYTE; others give their raw fields).
    std::vector<uint32_t> values(const std::string& bytes, const TiffEntry& entry) const;
    // Sets value `index` of the entry, in its type's size.
    void setValue(std::string& bytes, const TiffEntry& entry, size_t index, uint64_t value) const;
};

// The directories of `bytes` ("II*\0…", "MM\0*…", BigTIFF's "II+\0…", "MM\0+…"); nullopt
// when the header is not TIFF's.
std::optional<TiffLayout> parseTiff(const std::string& bytes);

// Damages one entry: its type, count, offset or a value; returns what it did.
std::string damageTiffEntry(std::string& bytes, const TiffLayout& layout, const TiffEntry& entry, Random& random);

// Damages a TIFF structure anywhere: an entry, an IFD's entry count or next-IFD link, the
// first-IFD offset. Used for the EXIF blocks inside PNG, JPEG and WebP files.
std::string damageTiffStructure(std::string& bytes, Random& random);

// A small valid EXIF block (a TIFF structure: IFD0 with an EXIF sub-IFD), made from `random`
// in either byte order, for files that had none.
std::string makeExifBlock(Random& random);

}  // namespace fuzz
