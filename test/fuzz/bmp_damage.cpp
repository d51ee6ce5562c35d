// BMP: the file header and the DIB header are fixed fields, changed in place; the palette
// and the (RLE) pixel data follow. BMP has no checksums.
#include <algorithm>

#include "bytes.h"
#include "formats.h"
#include "interesting.h"

namespace fuzz {

namespace {

// Offsets of BITMAPINFOHEADER (and later) fields; OS/2's 12-byte core header has 16-bit sizes.
constexpr size_t kOffBits = 10, kHeaderSize = 14, kWidth = 18, kHeight = 22, kPlanes = 26, kBitCount = 28,
                 kCompression = 30, kSizeImage = 34, kClrUsed = 46, kMasks = 54;

bool isCoreHeader(const std::string& file) { return getLE(file, kHeaderSize, 4) == 12; }

std::string setField(std::string& file, size_t at, int size, const char* name, int64_t value) {
    const uint32_t old = getLE(file, at, size);
    putLE(file, at, size, uint64_t(value));
    return std::string(name) + " " + std::to_string(old) + " -> " + std::to_string(value);
}

std::string damageSize(std::string& file, Random& random) {
    if (isCoreHeader(file)) {
        const size_t at = random.percent(50) ? 18 : 20;
        return setField(file, at, 2, "core header size", int64_t(interestingValue(random, getLE(file, at, 2), 16)));
    }
    const bool height = random.percent(50);
    const size_t at = height ? kHeight : kWidth;
    const int32_t old = int32_t(getLE(file, at, 4));
    // Negative heights are legal (top-down); negative widths are not.
    const int64_t value = random.percent(20) ? -int64_t(old) : interestingSigned(random, old, 32);
    return setField(file, at, 4, height ? "biHeight" : "biWidth", value);
}

std::string damagePixelFormat(std::string& file, Random& random) {
    switch (random.below(4)) {
        case 0: {
            const uint64_t counts[] = {0, 1, 2, 3, 4, 8, 15, 16, 24, 32, 48, 64, 255, 65535};
            return setField(file, kBitCount, 2, "biBitCount", int64_t(counts[random.below(std::size(counts))]));
        }
        case 1: {
            const uint64_t compressions[] = {0, 1, 2, 3, 4, 5, 6, 11, 12, 13, 255, 0xFFFFFFFF};
            return setField(file, kCompression, 4, "biCompression",
                            int64_t(compressions[random.below(std::size(compressions))]));
        }
        case 2: return setField(file, kPlanes, 2, "biPlanes", random.percent(50) ? 0 : random.between(2, 11));
        default: {
            // Colour masks (BI_BITFIELDS): none, all bits, overlapping, one bit, one field.
            const uint64_t masks[] = {0, 0xFFFFFFFF, 0x0000FFFF, 0x00000001, 0x80000000, 0x00FF00FF, 0x7C00, 0xF800};
            const size_t at = kMasks + 4 * random.below(4);
            return setField(file, at, 4, "colour mask", int64_t(masks[random.below(std::size(masks))]));
        }
    }
}

std::string damageStructure(std::string& file, Random& random) {
    const uint32_t offbits = getLE(file, kOffBits, 4), header = getLE(file, kHeaderSize, 4);
    switch (random.below(5)) {
        case 0: {
            const uint64_t sizes[] = {0, 12, 16, 39, 40, 41, 52, 56, 64, 108, 124, 125, 255, 0xFFFFFFFF};
            return setField(file, kHeaderSize, 4, "biSize", int64_t(sizes[random.below(std::size(sizes))]));
        }
        case 1: {
            const uint64_t offsets[] = {
                0,           1,          14,        54, 14 + header - 1, offbits - 1, offbits + 1, file.size() - 1,
                file.size(), 0x7FFFFFFF, 0xFFFFFFFF};
            return setField(file, kOffBits, 4, "bfOffBits", int64_t(offsets[random.below(std::size(offsets))]));
        }
        case 2: {
            const uint32_t bits = getLE(file, kBitCount, 2);
            const uint64_t palette = bits < 32 ? uint64_t(1) << bits : 0;
            const uint64_t counts[] = {0, 1, 2, palette, palette + 1, 256, 257, 65536, 0x40000000, 0xFFFFFFFF};
            return setField(file, kClrUsed, 4, "biClrUsed", int64_t(counts[random.below(std::size(counts))]));
        }
        case 3: {
            const uint64_t size = random.percent(50) ? 0 : interestingValue(random, getLE(file, kSizeImage, 4), 32);
            return setField(file, random.percent(50) ? kSizeImage : 2, 4, "biSizeImage/bfSize", int64_t(size));
        }
        default: {
            // The palette shortened (or lengthened): the pixels move but bfOffBits does not.
            const size_t palette = 14 + header;
            if (palette >= offbits || offbits > file.size()) return "no palette";
            const size_t count = random.between(1, 64);
            if (random.percent(50))
                file.erase(palette + random.below(offbits - palette), std::min<size_t>(count, offbits - palette));
            else
                file.insert(palette, random.bytes(count));
            return "palette length changed by " + std::to_string(count) + " bytes";
        }
    }
}

std::string damageStream(std::string& file, Random& random) {
    const size_t pixels = getLE(file, kOffBits, 4);
    if (pixels >= file.size()) return "no pixel data";
    const size_t at = pixels + random.below(file.size() - pixels);
    const bool rle = !isCoreHeader(file) && (getLE(file, kCompression, 4) == 1 || getLE(file, kCompression, 4) == 2);
    if (rle && random.percent(70)) {
        // RLE escapes: a delta far away, an absolute run longer than the row, a long run,
        // an early end of line, or no end of bitmap.
        std::string codes;
        switch (random.below(5)) {
            case 0: codes = std::string("\0\2", 2) + char(random.byte()) + char(random.byte()); break;
            case 1: codes = std::string("\0", 1) + char(random.between(3, 255)) + random.bytes(random.below(64)); break;
            case 2: codes = std::string("\xFF", 1) + char(random.byte()); break;
            case 3: codes = std::string("\0\0", 2); break;
            default:
                file.resize(file.size() - std::min<size_t>(file.size() - pixels, 2));
                return "RLE end of bitmap removed";
        }
        // On a code boundary half the time: RLE codes are byte pairs from the start.
        const size_t where = random.percent(50) ? pixels + (at - pixels) / 2 * 2 : at;
        file.insert(where, codes);
        return "RLE codes inserted at " + std::to_string(where);
    }
    const size_t count = std::min<size_t>(file.size() - at, random.between(1, 32));
    file.replace(at, count, random.bytes(count));
    return std::to_string(count) + " random pixel bytes at " + std::to_string(at);
}

}  // namespace

std::string damageBmp(std::string& file, DamageKind kind, Random& random) {
    if (file.size() < kMasks) return "not a BMP";
    switch (kind) {
        case DamageKind::Size: return damageSize(file, random);
        case DamageKind::PixelFormat: return damagePixelFormat(file, random);
        case DamageKind::Structure: return damageStructure(file, random);
        default: return damageStream(file, random);
    }
}

}  // namespace fuzz
