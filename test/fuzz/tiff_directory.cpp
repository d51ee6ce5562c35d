#include "tiff_directory.h"

#include <algorithm>

#include "bytes.h"
#include "interesting.h"

namespace fuzz {

namespace {

// Tags whose value is the offset of another IFD: EXIF, GPS, interoperability, SubIFDs.
bool pointsToDirectory(uint16_t tag) { return tag == 0x8769 || tag == 0x8825 || tag == 0xA005 || tag == 330; }

void readDirectory(const std::string& bytes, TiffLayout& layout, uint64_t offset, int depth) {
    // A directory twice (a loop) or too many of them: stop, the reader has to cope with it.
    for (int chain = 0; chain < 8 && offset >= 8 && offset < bytes.size() && bytes.size() - offset >= 8; ++chain) {
        if (std::find(layout.directories.begin(), layout.directories.end(), offset) != layout.directories.end()) return;
        layout.directories.push_back(offset);
        const uint64_t count = layout.get(bytes, offset, layout.entryCountSize());
        std::vector<uint64_t> children;
        for (uint64_t i = 0;
             i < count && offset + layout.entryCountSize() + (i + 1) * layout.entrySize() <= bytes.size(); ++i) {
            TiffEntry entry{offset + layout.entryCountSize() + i * layout.entrySize(), 0, 0, 0, 0};
            entry.tag = uint16_t(layout.get(bytes, entry.at, 2));
            entry.type = uint16_t(layout.get(bytes, entry.at + 2, 2));
            entry.count = layout.get(bytes, layout.countAt(entry), layout.offsetSize());
            entry.value = layout.get(bytes, layout.valueAt(entry), layout.offsetSize());
            layout.entries.push_back(entry);
            if (pointsToDirectory(entry.tag) && depth == 0) children.push_back(entry.value);
        }
        for (uint64_t child : children) readDirectory(bytes, layout, child, depth + 1);
        offset = layout.get(bytes, layout.nextLinkAt(bytes, offset), layout.offsetSize());
    }
}

const char* typeName(uint16_t type) {
    static const char* names[] = {"0",         "BYTE",   "ASCII", "SHORT",     "LONG",  "RATIONAL", "SBYTE",
                                  "UNDEFINED", "SSHORT", "SLONG", "SRATIONAL", "FLOAT", "DOUBLE",   "IFD",
                                  "14",        "15",     "LONG8", "SLONG8",    "IFD8"};
    return type < std::size(names) ? names[type] : "unknown";
}

std::string describe(const TiffEntry& entry) {
    return "tag " + std::to_string(entry.tag) + " (" + typeName(entry.type) + " x" + std::to_string(entry.count) + ")";
}

}  // namespace

uint64_t TiffLayout::get(const std::string& bytes, size_t at, int size) const {
    if (size == 8) {
        const uint64_t first = get(bytes, at, 4), second = get(bytes, at + 4, 4);
        return little_endian ? first | second << 32 : first << 32 | second;
    }
    return little_endian ? getLE(bytes, at, size) : getBE(bytes, at, size);
}

size_t TiffLayout::nextLinkAt(const std::string& bytes, size_t directory) const {
    return directory + entryCountSize() + get(bytes, directory, entryCountSize()) * entrySize();
}

void TiffLayout::put(std::string& bytes, size_t at, int size, uint64_t value) const {
    little_endian ? putLE(bytes, at, size, value) : putBE(bytes, at, size, value);
}

const TiffEntry* TiffLayout::find(uint16_t tag) const {
    for (const TiffEntry& entry : entries)
        if (entry.tag == tag) return &entry;
    return nullptr;
}

int TiffLayout::typeSize(uint16_t type) {
    switch (type) {
        case 3:
        case 8: return 2;
        case 4:
        case 9:
        case 11:
        case 13: return 4;
        case 5:
        case 10:
        case 12:
        case 16:
        case 17:
        case 18: return 8;
        default: return 1;
    }
}

size_t TiffLayout::valuesAt(const TiffEntry& entry) const {
    return entry.count * typeSize(entry.type) <= uint64_t(offsetSize()) ? valueAt(entry) : entry.value;
}

std::vector<uint32_t> TiffLayout::values(const std::string& bytes, const TiffEntry& entry) const {
    std::vector<uint32_t> out;
    const int size = std::min(4, typeSize(entry.type));
    const size_t at = valuesAt(entry);
    for (uint32_t i = 0; i < entry.count && at + (i + 1) * size_t(size) <= bytes.size() && i < 4096; ++i)
        out.push_back(uint32_t(get(bytes, at + i * size_t(size), size)));
    return out;
}

void TiffLayout::setValue(std::string& bytes, const TiffEntry& entry, size_t index, uint64_t value) const {
    const int size = std::min(4, typeSize(entry.type));
    put(bytes, valuesAt(entry) + index * size_t(size), size, value);
}

std::optional<TiffLayout> parseTiff(const std::string& bytes) {
    if (bytes.size() < 8) return std::nullopt;
    TiffLayout layout;
    const std::string header = bytes.substr(0, 4);
    layout.little_endian = header[0] == 'I';
    layout.big = header == std::string("II+\0", 4) || header == std::string("MM\0+", 4);
    if (!layout.big && header != std::string("II*\0", 4) && header != std::string("MM\0*", 4)) return std::nullopt;
    readDirectory(bytes, layout, layout.get(bytes, layout.firstLinkAt(), layout.offsetSize()), 0);
    return layout;
}

std::string damageTiffEntry(std::string& bytes, const TiffLayout& layout, const TiffEntry& entry, Random& random) {
    switch (random.below(4)) {
        case 0: {
            const uint16_t types[] = {0, 1, 2, 3, 4, 5, 7, 9, 11, 12, 13, 14, 255, 65535};
            const uint16_t type = types[random.below(std::size(types))];
            layout.put(bytes, entry.at + 2, 2, type);
            return describe(entry) + ": type -> " + std::to_string(type);
        }
        case 1: {
            const uint64_t count = interestingValue(random, entry.count, 8 * layout.offsetSize());
            layout.put(bytes, layout.countAt(entry), layout.offsetSize(), count);
            return describe(entry) + ": count -> " + std::to_string(count);
        }
        case 2: {
            const uint64_t value = random.percent(50) ? interestingValue(random, entry.value, 8 * layout.offsetSize())
                                                      : random.below(bytes.size() + 16);
            layout.put(bytes, layout.valueAt(entry), layout.offsetSize(), value);
            return describe(entry) + ": value/offset field -> " + std::to_string(value);
        }
        default: {
            const std::vector<uint32_t> values = layout.values(bytes, entry);
            if (values.empty()) return describe(entry) + ": no values to change";
            const size_t index = random.below(values.size());
            const uint64_t value =
                interestingValue(random, values[index], 8 * std::min(4, TiffLayout::typeSize(entry.type)));
            layout.setValue(bytes, entry, index, value);
            return describe(entry) + ": value " + std::to_string(index) + " " + std::to_string(values[index]) + " -> " +
                   std::to_string(value);
        }
    }
}

std::string damageTiffStructure(std::string& bytes, Random& random) {
    const std::optional<TiffLayout> layout = parseTiff(bytes);
    if (!layout || layout->entries.empty()) {
        if (bytes.size() < 5) return "TIFF structure too short";
        const size_t at = random.below(bytes.size());
        bytes[at] = char(random.byte());
        return "TIFF structure byte " + std::to_string(at) + " set";
    }
    switch (random.below(6)) {
        case 0: {
            const size_t ifd = random.pick(layout->directories);
            const int size = layout->entryCountSize();
            const uint64_t count = interestingValue(random, layout->get(bytes, ifd, size), 8 * size);
            layout->put(bytes, ifd, size, count);
            return "IFD at " + std::to_string(ifd) + ": entry count -> " + std::to_string(count);
        }
        case 1: {
            // The next-IFD link: to itself (a loop), into the middle of something, past the end.
            const size_t ifd = random.pick(layout->directories);
            const uint64_t target = random.percent(40) ? ifd : random.below(bytes.size() + 64);
            layout->put(bytes, layout->nextLinkAt(bytes, ifd), layout->offsetSize(), target);
            return "IFD at " + std::to_string(ifd) + ": next IFD -> " + std::to_string(target);
        }
        case 2: {
            const int size = layout->offsetSize();
            const uint64_t first =
                random.percent(30) ? interestingValue(random, layout->get(bytes, layout->firstLinkAt(), size), 8 * size)
                                   : random.below(bytes.size() + 16);
            layout->put(bytes, layout->firstLinkAt(), size, first);
            return "first IFD offset -> " + std::to_string(first);
        }
        default: return damageTiffEntry(bytes, *layout, random.pick(layout->entries), random);
    }
}

std::string makeExifBlock(Random& random) {
    const bool little = random.percent(50);
    TiffLayout order;
    order.little_endian = little;
    auto num = [&](int size, uint64_t value) {
        std::string out(size_t(size), '\0');
        order.put(out, 0, size, value);
        return out;
    };
    auto entry = [&](uint16_t tag, uint16_t type, uint32_t count, uint32_t value) {
        return num(2, tag) + num(2, type) + num(4, count) +
               num(4, type == 3 && count == 1 && !little ? value << 16 : value);
    };
    // Layout: header (8), IFD0 at 8 with 4 entries (2 + 48 + 4 = 54), EXIF IFD at 62 with
    // 3 entries (2 + 36 + 4 = 42), then the out-of-line values from 104.
    const uint32_t values = 104;
    std::string block = std::string(little ? "II*\0" : "MM\0*", 4) + num(4, 8);
    block += num(2, 4) + entry(0x010F, 2, 12, values) + entry(0x0112, 3, 1, uint32_t(random.between(1, 8))) +
             entry(0x011A, 5, 1, values + 12) + entry(0x8769, 4, 1, 62) + num(4, 0);
    block += num(2, 3) + entry(0x829A, 5, 1, values + 20) + entry(0x9003, 2, 20, values + 28) +
             entry(0x927C, 7, 16, values + 48) + num(4, 0);
    block += std::string("fuzz camera\0", 12) + num(4, 72) + num(4, 1) + num(4, 1) + num(4, 100) +
             std::string("2024:01:02 03:04:05\0", 20) + random.bytes(16);
    return block;
}

}  // namespace fuzz
