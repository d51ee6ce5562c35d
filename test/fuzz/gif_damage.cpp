// GIF: the logical screen, colour tables, extensions and image descriptors are located and
// their fields changed in place; the LZW data is damaged inside its sub-blocks, whose
// length bytes stay right unless they are the damage. GIF has no checksums.
#include <algorithm>

#include "bytes.h"
#include "formats.h"
#include "interesting.h"

namespace fuzz {

namespace {

struct SubBlocks {
    size_t begin = 0, end = 0;  // from the first length byte to past the terminating 0
};

struct ImageBlock {
    size_t descriptor = 0;  // the 0x2C byte
    size_t code_size = 0;   // the LZW minimum code size byte
    SubBlocks data;
};

struct Gif {
    std::vector<ImageBlock> images;
    std::vector<size_t> extensions;  // the 0x21 bytes
    std::vector<SubBlocks> sub_blocks;
    size_t trailer = std::string::npos;
};

size_t tableSize(uint8_t packed) { return packed & 0x80 ? 3 * (size_t(2) << (packed & 7)) : 0; }

SubBlocks walkSubBlocks(const std::string& file, size_t at) {
    SubBlocks blocks{at, at};
    while (at < file.size() && file[at] != '\0') at += 1 + uint8_t(file[at]);
    blocks.end = std::min(at + 1, file.size());
    return blocks;
}

Gif parseGif(const std::string& file) {
    Gif gif;
    size_t at = 13 + tableSize(uint8_t(file.size() > 10 ? file[10] : 0));
    while (at < file.size()) {
        const uint8_t type = uint8_t(file[at]);
        if (type == 0x3B) {
            gif.trailer = at;
            break;
        }
        if (type == 0x21) {
            gif.extensions.push_back(at);
            gif.sub_blocks.push_back(walkSubBlocks(file, at + 2));
            at = gif.sub_blocks.back().end;
        } else if (type == 0x2C) {
            ImageBlock image;
            image.descriptor = at;
            image.code_size = at + 10 + tableSize(uint8_t(at + 9 < file.size() ? file[at + 9] : 0));
            image.data = walkSubBlocks(file, image.code_size + 1);
            gif.sub_blocks.push_back(image.data);
            gif.images.push_back(image);
            at = image.data.end;
        } else {
            break;
        }
    }
    return gif;
}

std::string setByte(std::string& file, size_t at, const char* name, uint8_t value) {
    if (at >= file.size()) return std::string("no ") + name;
    const uint8_t old = uint8_t(file[at]);
    file[at] = char(value);
    return std::string(name) + " " + std::to_string(old) + " -> " + std::to_string(value);
}

std::string damageSize(std::string& file, const Gif& gif, Random& random) {
    const char* names[] = {"screen width", "screen height", "frame left", "frame top", "frame width", "frame height"};
    const size_t field = gif.images.empty() ? random.below(2) : random.below(6);
    const size_t at = field < 2 ? 6 + 2 * field : random.pick(gif.images).descriptor + 1 + 2 * (field - 2);
    const uint32_t old = getLE(file, at, 2);
    const uint64_t value = interestingValue(random, old, 16);
    putLE(file, at, 2, value);
    return std::string(names[field]) + " " + std::to_string(old) + " -> " + std::to_string(value);
}

std::string damagePixelFormat(std::string& file, const Gif& gif, Random& random) {
    const size_t image = gif.images.empty() ? 0 : random.pick(gif.images).descriptor;
    switch (random.below(5)) {
        case 0: {
            // Global colour table flag or size, the table itself left as it was.
            const uint8_t packed = uint8_t(file[10]);
            const uint8_t value = random.percent(50) ? packed ^ 0x80 : uint8_t((packed & ~7) | random.below(8));
            return setByte(file, 10, "screen flags (global table)", value);
        }
        case 1: {
            if (!image) return "no image";
            const uint8_t packed = uint8_t(file[image + 9]);
            const uint8_t masks[] = {0x80, 0x40, 0x07, 0x87, 0x3F};
            return setByte(file, image + 9, "frame flags (local table, interlace)",
                           packed ^ masks[random.below(std::size(masks))]);
        }
        case 2: {
            if (gif.images.empty()) return "no image";
            const uint8_t sizes[] = {0, 1, 2, 7, 9, 11, 12, 13, 255};
            return setByte(file, random.pick(gif.images).code_size, "LZW minimum code size",
                           sizes[random.below(std::size(sizes))]);
        }
        case 3: {
            // A graphic control extension: transparency flag and an index beyond the palette.
            for (size_t ext : gif.extensions)
                if (ext + 6 < file.size() && uint8_t(file[ext + 1]) == 0xF9) {
                    file[ext + 3] = char(uint8_t(file[ext + 3]) | 1);
                    return setByte(file, ext + 6, "transparent index", random.byte());
                }
            return "no graphic control extension";
        }
        default: return setByte(file, 10, "screen flags", random.byte());
    }
}

std::string damageStructure(std::string& file, const Gif& gif, Random& random) {
    switch (random.below(6)) {
        case 0: {
            // A sub-block length byte.
            if (gif.sub_blocks.empty()) return "no sub-blocks";
            const SubBlocks blocks = random.pick(gif.sub_blocks);
            std::vector<size_t> lengths;
            for (size_t at = blocks.begin; at < blocks.end && at < file.size(); at += 1 + uint8_t(file[at]))
                lengths.push_back(at);
            const size_t at = random.pick(lengths);
            const uint8_t old = uint8_t(file[at]);
            const uint8_t values[] = {0, 1, 255, uint8_t(old + 1), uint8_t(old - 1)};
            return setByte(file, at, "sub-block length", values[random.below(std::size(values))]);
        }
        case 1: {
            if (gif.images.empty()) return "no image";
            const SubBlocks data = random.pick(gif.images).data;
            file.erase(data.end - 1, 1);
            return "image data terminator removed";
        }
        case 2:
            if (gif.trailer == std::string::npos) return "no trailer";
            file.erase(gif.trailer);
            return "trailer removed";
        case 3: {
            const size_t blocks = 13 + tableSize(uint8_t(file[10]));
            const uint8_t labels[] = {0x2D, 0x00, 0xFF, 0x21, 0x2C};
            return setByte(file, std::min(blocks, file.size() - 1), "first block type",
                           labels[random.below(std::size(labels))]);
        }
        case 4: {
            // The global table cut short while the flag still announces it.
            const size_t table = tableSize(uint8_t(file[10]));
            if (!table) return "no global table";
            const size_t cut = random.between(1, int64_t(table));
            file.erase(13, cut);
            return "global colour table " + std::to_string(cut) + " bytes short";
        }
        default: {
            // Another frame: a copy of the first with other geometry, or an application
            // extension (NETSCAPE looping) with wrong lengths.
            if (gif.images.empty() || gif.trailer == std::string::npos) return "no image";
            std::string block;
            if (random.percent(50)) {
                const ImageBlock& image = gif.images.front();
                block = file.substr(image.descriptor, image.data.end - image.descriptor);
                putLE(block, 1 + 2 * random.below(4), 2, interestingValue(random, 10, 16));
            } else {
                block = std::string("\x21\xFF\x0BNETSCAPE2.0", 14) + char(random.below(6)) + "\x01" +
                        random.bytes(random.below(4)) + '\0';
            }
            file.insert(gif.trailer, block);
            return "added a block of " + std::to_string(block.size()) + " bytes";
        }
    }
}

std::string damageStream(std::string& file, const Gif& gif, Random& random) {
    if (gif.images.empty()) return "no image";
    const SubBlocks data = random.pick(gif.images).data;
    std::vector<size_t> bytes;  // data bytes, not length bytes
    for (size_t at = data.begin; at + 1 < data.end && at < file.size(); at += 1 + uint8_t(file[at]))
        for (size_t i = at + 1; i <= at + uint8_t(file[at]) && i < file.size(); ++i) bytes.push_back(i);
    if (bytes.empty()) return "no image data";
    if (random.percent(25)) {
        const size_t at = random.pick(bytes);
        file.resize(at);
        return "cut inside the LZW data at " + std::to_string(at);
    }
    const int count = int(random.between(1, 16));
    for (int i = 0; i < count; ++i) file[random.pick(bytes)] = char(random.byte());
    return std::to_string(count) + " LZW data bytes set";
}

}  // namespace

std::string damageGif(std::string& file, DamageKind kind, Random& random) {
    if (file.size() < 13) return "not a GIF";
    const Gif gif = parseGif(file);
    switch (kind) {
        case DamageKind::Size: return damageSize(file, gif, random);
        case DamageKind::PixelFormat: return damagePixelFormat(file, gif, random);
        case DamageKind::Structure: return damageStructure(file, gif, random);
        default: return damageStream(file, gif, random);
    }
}

}  // namespace fuzz
