// PNG: the file is taken apart into chunks, a chunk is changed, and the file is put together
// again with every length and CRC right, so the damage reaches libpng's checks of the fields
// rather than its CRC check. A lying length gets the CRC libpng will compute where it reads.
#include <algorithm>

#include "bytes.h"
#include "formats.h"
#include "interesting.h"

namespace fuzz {

namespace {

const std::string kSignature("\x89PNG\r\n\x1a\n", 8);

struct Chunk {
    std::string type;
    std::string data;
};

std::vector<Chunk> chunksOf(const std::string& file) {
    std::vector<Chunk> chunks;
    for (size_t at = 8; at + 12 <= file.size();) {
        const uint32_t length = getBE(file, at, 4);
        if (length > file.size() - at - 12) break;
        chunks.push_back({file.substr(at + 4, 4), file.substr(at + 8, length)});
        at += 12 + length;
    }
    return chunks;
}

std::string fileOf(const std::vector<Chunk>& chunks) {
    std::string file = kSignature;
    for (const Chunk& chunk : chunks)
        file += be(4, chunk.data.size()) + chunk.type + chunk.data + be(4, crc32Of(chunk.type + chunk.data));
    return file;
}

Chunk* find(std::vector<Chunk>& chunks, const std::string& type) {
    for (Chunk& chunk : chunks)
        if (chunk.type == type) return &chunk;
    return nullptr;
}

// The IDAT chunks' data joined, and the chunks replaced by `count` IDATs holding `stream`.
std::string joinedIdat(const std::vector<Chunk>& chunks) {
    std::string stream;
    for (const Chunk& chunk : chunks)
        if (chunk.type == "IDAT") stream += chunk.data;
    return stream;
}

void replaceIdat(std::vector<Chunk>& chunks, const std::string& stream, size_t pieces) {
    auto first = std::find_if(chunks.begin(), chunks.end(), [](const Chunk& c) { return c.type == "IDAT"; });
    size_t at = first == chunks.end() ? chunks.size() - 1 : size_t(first - chunks.begin());
    std::erase_if(chunks, [](const Chunk& c) { return c.type == "IDAT"; });
    at = std::min(at, chunks.size());
    const size_t step = std::max<size_t>(1, (stream.size() + pieces - 1) / std::max<size_t>(1, pieces));
    std::vector<Chunk> idat;
    for (size_t offset = 0; offset < stream.size() || idat.empty(); offset += step)
        idat.push_back({"IDAT", stream.substr(std::min(offset, stream.size()), step)});
    chunks.insert(chunks.begin() + long(at), idat.begin(), idat.end());
}

std::string damageSize(std::vector<Chunk>& chunks, Random& random) {
    Chunk* ihdr = find(chunks, "IHDR");
    if (!ihdr) return "no IHDR";
    const uint32_t width = getBE(ihdr->data, 0, 4), height = getBE(ihdr->data, 4, 4);
    switch (random.below(4)) {
        case 0: {
            const uint64_t value = interestingValue(random, width, 32);
            putBE(ihdr->data, 0, 4, value);
            return "IHDR width " + std::to_string(width) + " -> " + std::to_string(value);
        }
        case 1: {
            const uint64_t value = interestingValue(random, height, 32);
            putBE(ihdr->data, 4, 4, value);
            return "IHDR height " + std::to_string(height) + " -> " + std::to_string(value);
        }
        case 2:
            putBE(ihdr->data, 0, 4, height);
            putBE(ihdr->data, 4, 4, width);
            return "IHDR width and height swapped";
        default: {
            const uint64_t w = random.below(width * 2 + 2), h = random.below(height * 2 + 2);
            putBE(ihdr->data, 0, 4, w);
            putBE(ihdr->data, 4, 4, h);
            return "IHDR size -> " + std::to_string(w) + "x" + std::to_string(h);
        }
    }
}

std::string damagePixelFormat(std::vector<Chunk>& chunks, Random& random) {
    Chunk* ihdr = find(chunks, "IHDR");
    if (!ihdr || ihdr->data.size() < 13) return "no IHDR";
    struct Field {
        const char* name;
        size_t at;
        std::vector<int> values;
    };
    const std::vector<Field> fields = {{"bit depth", 8, {0, 1, 2, 3, 4, 5, 7, 8, 9, 16, 32, 255}},
                                       {"colour type", 9, {0, 1, 2, 3, 4, 5, 6, 7, 8, 255}},
                                       {"compression method", 10, {1, 8, 255}},
                                       {"filter method", 11, {1, 64, 255}},
                                       {"interlace method", 12, {0, 1, 2, 255}}};
    if (random.percent(30)) {
        // A legal depth and colour type, which the palette and the data no longer match.
        const int legal[][2] = {{1, 0}, {2, 0}, {4, 0}, {8, 0}, {16, 0}, {8, 2}, {16, 2}, {1, 3},
                                {2, 3}, {4, 3}, {8, 3}, {8, 4}, {16, 4}, {8, 6}, {16, 6}};
        const auto& pair = legal[random.below(std::size(legal))];
        ihdr->data[8] = char(pair[0]);
        ihdr->data[9] = char(pair[1]);
        return "IHDR depth " + std::to_string(pair[0]) + ", colour type " + std::to_string(pair[1]);
    }
    const Field& field = random.pick(fields);
    const int value = random.pick(field.values);
    const int old = uint8_t(ihdr->data[field.at]);
    ihdr->data[field.at] = char(value);
    return std::string("IHDR ") + field.name + " " + std::to_string(old) + " -> " + std::to_string(value);
}

// Ancillary chunks whose content readers parse: EXIF (OIIO's own TIFF-directory parser),
// ICC profiles and compressed text (zlib), physical size and gamma (divisions).
Chunk damagedAncillary(Random& random) {
    switch (random.below(7)) {
        case 0: {
            // A TIFF directory: a few entries, counts and offsets that may point anywhere.
            std::string exif = std::string(random.percent(50) ? "II*\0" : "MM\0*", 4);
            const bool little = exif[0] == 'I';
            auto num = [&](int size, uint64_t value) { return little ? le(size, value) : be(size, value); };
            exif += num(4, random.percent(70) ? 8 : interestingValue(random, 8, 32));
            const int entries = int(random.between(0, 6));
            exif += num(2, random.percent(80) ? uint64_t(entries) : interestingValue(random, uint64_t(entries), 16));
            const uint16_t tags[] = {0x010F, 0x0112, 0x011A, 0x8769, 0x8825, 0x9003, 0x829A, 0xA002, 0x927C};
            for (int i = 0; i < entries; ++i)
                exif += num(2, tags[random.below(std::size(tags))]) + num(2, random.between(0, 13)) +
                        num(4, interestingValue(random, 1, 32)) + num(4, interestingValue(random, 8, 32));
            exif += num(4, random.percent(50) ? 0 : interestingValue(random, 8, 32)) + random.bytes(random.below(40));
            return {"eXIf", exif};
        }
        case 1: {
            std::string profile =
                random.percent(50) ? zlibCompress(random.bytes(random.below(300))) : random.bytes(random.below(64));
            if (!profile.empty() && random.percent(50)) profile.resize(random.below(profile.size()));
            return {"iCCP", std::string("icc\0\0", 5) + profile};
        }
        case 2: return {"zTXt", std::string("Comment\0\0", 9) + random.bytes(random.below(40))};
        case 3: return {"iTXt", std::string("XML:com.adobe.xmp\0\1\0\0\0", 22) + random.bytes(random.below(40))};
        case 4:
            return {"pHYs", be(4, interestingValue(random, 2835, 32)) + be(4, interestingValue(random, 2835, 32)) +
                                char(random.below(3))};
        case 5: return {"gAMA", be(4, interestingValue(random, 45455, 32))};
        default: return {"tEXt", random.bytes(random.below(90))};  // the keyword's NUL may be missing
    }
}

// The length field of one chunk lies; the CRC is the one libpng computes over what it reads.
std::string lieAboutLength(const std::vector<Chunk>& chunks, std::string& file, Random& random) {
    file = fileOf(chunks);
    if (chunks.empty()) return "no chunks";
    const size_t index = random.below(chunks.size());
    size_t at = 8;
    for (size_t i = 0; i < index; ++i) at += 12 + chunks[i].data.size();
    const uint64_t length = interestingValue(random, chunks[index].data.size(), 32);
    putBE(file, at, 4, length);
    if (at + 12 + length <= file.size()) putBE(file, at + 8 + length, 4, crc32Of(file.substr(at + 4, 4 + length)));
    return chunks[index].type + " length " + std::to_string(chunks[index].data.size()) + " -> " +
           std::to_string(length);
}

std::string damageStructure(std::vector<Chunk>& chunks, Random& random) {
    if (chunks.empty()) return "no chunks";
    const size_t index = random.below(chunks.size());
    Chunk& chunk = chunks[index];
    switch (random.below(7)) {
        case 0: {
            // Data of another size, consistently: IHDR, PLTE and tRNS sizes are checked separately.
            const char* sized[] = {"IHDR", "PLTE", "tRNS", "IEND", "IDAT"};
            Chunk* target = find(chunks, sized[random.below(std::size(sized))]);
            if (!target) target = &chunk;
            const size_t old = target->data.size();
            const size_t sizes[] = {
                0, 1, 2, 3, 12, 14, old ? old - 1 : 0, old + 1, old + 3, 768, 771, 1024, size_t(random.below(2000))};
            const size_t size = sizes[random.below(std::size(sizes))];
            target->data.resize(size, char(random.byte()));
            return target->type + " data " + std::to_string(old) + " -> " + std::to_string(size) + " bytes";
        }
        case 1: {
            const std::string type = chunk.type;
            chunks.erase(chunks.begin() + long(index));
            return "removed " + type;
        }
        case 2: {
            const Chunk copy = chunk;
            chunks.insert(chunks.begin() + long(random.below(chunks.size() + 1)), copy);
            return "duplicated " + copy.type;
        }
        case 3: {
            const size_t other = random.below(chunks.size());
            std::swap(chunks[index], chunks[other]);
            return "swapped " + chunks[other].type + " and " + chunks[index].type;
        }
        case 4: {
            Chunk added = damagedAncillary(random);
            if (random.percent(15))
                added = {"PLTE", random.bytes(3 * random.between(0, 300))};
            else if (random.percent(15))
                added = {"tRNS", random.bytes(random.below(300))};
            chunks.insert(chunks.begin() + long(1 + random.below(chunks.size())), added);
            return "inserted " + added.type + " of " + std::to_string(added.data.size()) + " bytes";
        }
        case 5: {
            const size_t pieces = size_t(random.between(2, 64));
            replaceIdat(chunks, joinedIdat(chunks), pieces);
            if (random.percent(50))
                chunks.insert(chunks.begin() + long(1 + random.below(chunks.size())), Chunk{"IDAT", ""});
            return "image data split into " + std::to_string(pieces) + " IDAT chunks";
        }
        default: {
            // An unknown critical chunk (upper-case first letter): readers must stop at it.
            chunks.insert(chunks.begin() + long(1 + random.below(chunks.size())),
                          Chunk{"FUZz", random.bytes(random.below(20))});
            return "inserted unknown critical chunk";
        }
    }
}

std::string damageStream(std::vector<Chunk>& chunks, Random& random) {
    const std::string stream = joinedIdat(chunks);
    if (random.percent(60)) {
        // Damage inside the filtered scanlines, recompressed: a valid zlib stream and
        // Adler-32 carrying wrong filter types and wrong amounts of data.
        std::optional<std::string> scanlines = zlibDecompress(stream);
        if (!scanlines || scanlines->empty()) return "image data does not decompress";
        std::string what;
        switch (random.below(4)) {
            case 0: {
                const size_t at = random.below(scanlines->size());
                (*scanlines)[at] = char(random.between(5, 255));
                what = "byte " + std::to_string(at) + " of the scanlines (a filter type, or a sample) set";
                break;
            }
            case 1: {
                const size_t cut = random.between(1, int64_t(scanlines->size()));
                scanlines->resize(scanlines->size() - cut);
                what = std::to_string(cut) + " bytes fewer scanline data";
                break;
            }
            case 2: {
                const size_t extra = random.between(1, 4096);
                *scanlines += random.bytes(extra);
                what = std::to_string(extra) + " bytes more scanline data";
                break;
            }
            default: {
                const size_t at = random.below(scanlines->size()),
                             count = std::min<size_t>(scanlines->size() - at, random.between(1, 64));
                scanlines->replace(at, count, random.bytes(count));
                what = std::to_string(count) + " random scanline bytes at " + std::to_string(at);
            }
        }
        replaceIdat(chunks, zlibCompress(*scanlines), 1 + random.below(3));
        return what + ", recompressed";
    }
    // Damage to the deflate stream itself (inflate's checks; the chunk CRCs stay right).
    std::string damaged = stream;
    if (damaged.size() < 3) return "image data too short";
    std::string what;
    switch (random.below(3)) {
        case 0: {
            const uint8_t headers[][2] = {{0x88, 0x1D}, {0xF8, 0x01}, {0x78, 0xBB}, {0x79, 0x9C}, {0x08, 0x1D}};
            const auto& header = headers[random.below(std::size(headers))];
            damaged[0] = char(header[0]);
            damaged[1] = char(header[1]);
            what = "zlib header damaged";
            break;
        }
        case 1: {
            const size_t at = 2 + random.below(damaged.size() - 2);
            damaged[at] = char(uint8_t(damaged[at]) ^ (1u << random.below(8)));
            what = "bit flipped in the deflate stream at " + std::to_string(at);
            break;
        }
        default: {
            const size_t at = 2 + random.below(damaged.size() - 2),
                         count = std::min<size_t>(damaged.size() - at, random.between(1, 16));
            damaged.replace(at, count, random.bytes(count));
            what = std::to_string(count) + " random bytes in the deflate stream";
        }
    }
    replaceIdat(chunks, damaged, 1);
    return what;
}

}  // namespace

void repairPngCrcs(std::string& file) {
    for (size_t at = 8; at + 12 <= file.size();) {
        const uint64_t length = getBE(file, at, 4);
        if (at + 12 + length > file.size()) return;
        putBE(file, at + 8 + length, 4, crc32Of(file.substr(at + 4, 4 + length)));
        at += 12 + length;
    }
}

std::string damagePng(std::string& file, DamageKind kind, Random& random) {
    std::vector<Chunk> chunks = chunksOf(file);
    std::string what;
    switch (kind) {
        case DamageKind::Size: what = damageSize(chunks, random); break;
        case DamageKind::PixelFormat: what = damagePixelFormat(chunks, random); break;
        case DamageKind::Structure:
            if (random.percent(20)) return lieAboutLength(chunks, file, random);
            what = damageStructure(chunks, random);
            break;
        default: what = damageStream(chunks, random); break;
    }
    file = fileOf(chunks);
    return what;
}

}  // namespace fuzz
