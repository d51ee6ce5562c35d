// Targa: the 18-byte header's fields, the colour map, the (RLE) pixel data, and the TGA 2.0
// footer and extension area are changed in place. Targa has no signature (ddtup knows it by
// its extension) and no checksums.
#include <algorithm>

#include "bytes.h"
#include "formats.h"
#include "interesting.h"

namespace fuzz {

namespace {

const std::string kFooterSignature("TRUEVISION-XFILE.\0", 18);

size_t pixelDataStart(const std::string& file) {
    const size_t map_bytes = size_t(getLE(file, 5, 2)) * ((uint8_t(file[7]) + 7) / 8);
    return 18 + uint8_t(file[0]) + (file[1] ? map_bytes : 0);
}

bool hasFooter(const std::string& file) {
    return file.size() >= 44 && file.compare(file.size() - 18, 18, kFooterSignature) == 0;
}

// Where the pixels end: at the extension area or the footer of a TGA 2.0 file.
size_t pixelDataEnd(const std::string& file) {
    if (!hasFooter(file)) return file.size();
    const size_t footer = file.size() - 26, extension = getLE(file, footer, 4);
    return extension && extension < footer ? extension : footer;
}

std::string setByte(std::string& file, size_t at, const char* name, uint8_t value) {
    const uint8_t old = uint8_t(file[at]);
    file[at] = char(value);
    return std::string(name) + " " + std::to_string(old) + " -> " + std::to_string(value);
}

std::string setShort(std::string& file, size_t at, const char* name, uint64_t value) {
    const uint32_t old = getLE(file, at, 2);
    putLE(file, at, 2, value);
    return std::string(name) + " " + std::to_string(old) + " -> " + std::to_string(value & 0xFFFF);
}

std::string damageSize(std::string& file, Random& random) {
    const char* names[] = {"x origin", "y origin", "width", "height"};
    const size_t field = random.percent(80) ? 2 + random.below(2) : random.below(2);
    const size_t at = 8 + 2 * field;
    return setShort(file, at, names[field], interestingValue(random, getLE(file, at, 2), 16));
}

std::string damagePixelFormat(std::string& file, Random& random) {
    switch (random.below(5)) {
        case 0: {
            const uint8_t types[] = {0, 1, 2, 3, 9, 10, 11, 32, 33, 255};
            return setByte(file, 2, "image type", types[random.below(std::size(types))]);
        }
        case 1: {
            const uint8_t depths[] = {0, 1, 8, 15, 16, 24, 32, 33, 64, 255};
            return setByte(file, 16, "pixel depth", depths[random.below(std::size(depths))]);
        }
        case 2: {
            // Alpha bits (0-3), origin (4-5), interleaving (6-7).
            const uint8_t masks[] = {0x01, 0x08, 0x0F, 0x10, 0x20, 0x30, 0xC0};
            return setByte(file, 17, "descriptor", uint8_t(file[17]) ^ masks[random.below(std::size(masks))]);
        }
        case 3: {
            const uint8_t types[] = {0, 1, 2, 255};
            return setByte(file, 1, "colour map type", types[random.below(std::size(types))]);
        }
        default: {
            const uint8_t sizes[] = {0, 8, 15, 16, 24, 32, 33, 255};
            return setByte(file, 7, "colour map entry size", sizes[random.below(std::size(sizes))]);
        }
    }
}

std::string damageFooter(std::string& file, Random& random) {
    if (!hasFooter(file)) {
        // Add one pointing anywhere: OIIO reads the extension area it names.
        const uint64_t offset =
            random.percent(50) ? random.below(file.size() + 600) : interestingValue(random, file.size(), 32);
        file += le(4, offset) + le(4, 0) + kFooterSignature;
        return "TGA 2.0 footer added, extension area at " + std::to_string(offset);
    }
    const size_t footer = file.size() - 26;
    const size_t extension = getLE(file, footer, 4);
    switch (random.below(4)) {
        case 0: {
            const uint64_t offset =
                random.percent(50) ? random.below(file.size() + 600) : interestingValue(random, extension, 32);
            putLE(file, footer + (random.percent(80) ? 0 : 4), 4, offset);
            return "footer extension/developer offset -> " + std::to_string(offset);
        }
        case 1: file[file.size() - 2 - random.below(16)] = char(random.byte()); return "footer signature damaged";
        default: {
            // Inside the extension area: its size, the gamma and aspect ratios (a zero
            // denominator), and the offsets of the thumbnail and the tables.
            if (!extension || extension + 495 > footer) return "no extension area";
            const size_t fields[] = {0, 474, 476, 478, 480, 482, 486, 490, 494};
            const size_t at = extension + fields[random.below(std::size(fields))];
            const bool wide = at >= extension + 482 && at < extension + 494;
            const uint64_t value =
                random.percent(40) ? 0 : interestingValue(random, getLE(file, at, wide ? 4 : 2), wide ? 32 : 16);
            putLE(file, at, wide ? 4 : 2, value);
            return "extension area field at +" + std::to_string(at - extension) + " -> " + std::to_string(value);
        }
    }
}

std::string damageStructure(std::string& file, Random& random) {
    switch (random.below(4)) {
        case 0: return setByte(file, 0, "ID length", random.percent(50) ? 255 : random.byte());
        case 1: return setShort(file, 3, "colour map first entry", interestingValue(random, getLE(file, 3, 2), 16));
        case 2: return setShort(file, 5, "colour map length", interestingValue(random, getLE(file, 5, 2), 16));
        default: return damageFooter(file, random);
    }
}

std::string damageStream(std::string& file, Random& random) {
    const size_t begin = pixelDataStart(file);
    const size_t end = pixelDataEnd(file);
    if (begin >= end) return "no pixel data";
    const size_t at = begin + random.below(end - begin);
    const bool rle = uint8_t(file[2]) >= 9;
    if (rle && random.percent(60)) {
        // A packet header: a long run or raw packet, crossing the row or the image's end.
        const uint8_t header = random.percent(50) ? 0xFF : uint8_t(random.below(128)) | (random.percent(50) ? 0x80 : 0);
        file.insert(at, 1, char(header));
        return "RLE packet header " + std::to_string(header) + " inserted at " + std::to_string(at);
    }
    const size_t count = std::min<size_t>(end - at, random.between(1, 16));
    // Colour-mapped pixels are indices: 0xFF is beyond a short map.
    file.replace(at, count, random.percent(30) ? std::string(count, '\xFF') : random.bytes(count));
    return std::to_string(count) + " pixel bytes set at " + std::to_string(at);
}

}  // namespace

std::string damageTarga(std::string& file, DamageKind kind, Random& random) {
    if (file.size() < 18) return "not a Targa file";
    switch (kind) {
        case DamageKind::Size: return damageSize(file, random);
        case DamageKind::PixelFormat: return damagePixelFormat(file, random);
        case DamageKind::Structure: return damageStructure(file, random);
        default: return damageStream(file, random);
    }
}

}  // namespace fuzz
