// OpenEXR: the header's attributes are taken apart and changed; the offset table after the
// header is moved along when the header changes size, so the chunks are still found unless
// the table is the damage. Single-part files, scanline or tiled. EXR has no checksums.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "bytes.h"
#include "formats.h"
#include "interesting.h"

namespace fuzz {

namespace {

struct Attribute {
    std::string name, type, value;
};

struct Exr {
    uint32_t version = 0;  // version number and flags
    std::vector<Attribute> attributes;
    std::vector<uint64_t> offsets;  // the chunk offset table
    std::string chunks;             // everything after the table
    size_t original_chunks_at = 0;  // where the chunks began in the file read

    Attribute* find(const std::string& name) {
        for (Attribute& a : attributes)
            if (a.name == name) return &a;
        return nullptr;
    }
};

std::optional<Exr> parseExr(const std::string& file) {
    if (file.size() < 8) return std::nullopt;
    Exr exr;
    exr.version = getLE(file, 4, 4);
    size_t at = 8;
    while (at < file.size() && file[at] != '\0') {
        const size_t name_end = file.find('\0', at);
        const size_t type_end = name_end == std::string::npos ? name_end : file.find('\0', name_end + 1);
        if (type_end == std::string::npos || type_end + 5 > file.size()) return std::nullopt;
        const uint32_t size = getLE(file, type_end + 1, 4);
        if (size > file.size() - type_end - 5) return std::nullopt;
        exr.attributes.push_back({file.substr(at, name_end - at), file.substr(name_end + 1, type_end - name_end - 1),
                                  file.substr(type_end + 5, size)});
        at = type_end + 5 + size;
    }
    const size_t table = at + 1;
    // The table runs up to the first chunk, which its first entry names.
    const uint64_t first = getLE64(file, table);
    if (first <= table || first > file.size() || (first - table) % 8) return std::nullopt;
    for (size_t entry = table; entry < first; entry += 8) exr.offsets.push_back(getLE64(file, entry));
    exr.chunks = file.substr(first);
    exr.original_chunks_at = first;
    return exr;
}

std::string headerOf(const Exr& exr) {
    std::string header = "\x76\x2f\x31\x01" + le(4, exr.version);
    for (const Attribute& a : exr.attributes) header += a.name + '\0' + a.type + '\0' + le(4, a.value.size()) + a.value;
    return header + '\0';
}

std::string fileOf(const Exr& exr) {
    const std::string header = headerOf(exr);
    const int64_t shift = int64_t(header.size() + exr.offsets.size() * 8) - int64_t(exr.original_chunks_at);
    std::string file = header;
    for (uint64_t offset : exr.offsets) file += le(8, offset + uint64_t(shift));
    return file + exr.chunks;
}

std::string damageWindow(Exr& exr, Random& random) {
    Attribute* window = exr.find(random.percent(70) ? "dataWindow" : "displayWindow");
    if (!window || window->value.size() < 16) return "no window";
    const char* names[] = {"xMin", "yMin", "xMax", "yMax"};
    if (random.percent(20)) {
        // Max below min.
        const int64_t x_min = int32_t(getLE(window->value, 0, 4));
        putLE(window->value, 8, 4, uint64_t(x_min - random.between(1, 3)));
        return window->name + " xMax below xMin";
    }
    const size_t field = random.below(4);
    const int32_t old = int32_t(getLE(window->value, field * 4, 4));
    const int64_t value = interestingSigned(random, old, 32);
    putLE(window->value, field * 4, 4, uint64_t(value));
    return window->name + " " + names[field] + " " + std::to_string(old) + " -> " + std::to_string(value);
}

// Channel list entries: name, pixel type, pLinear and reserved bytes, x and y sampling.
struct Channel {
    std::string name;
    std::string fields;  // the 16 bytes after the name
};

std::vector<Channel> channelsOf(const std::string& value) {
    std::vector<Channel> channels;
    for (size_t at = 0; at < value.size() && value[at] != '\0';) {
        const size_t end = value.find('\0', at);
        if (end == std::string::npos || end + 17 > value.size()) break;
        channels.push_back({value.substr(at, end - at), value.substr(end + 1, 16)});
        at = end + 17;
    }
    return channels;
}

std::string channelListOf(const std::vector<Channel>& channels) {
    std::string value;
    for (const Channel& c : channels) value += c.name + '\0' + c.fields;
    return value + '\0';
}

std::string damageChannels(Exr& exr, Random& random) {
    Attribute* list = exr.find("channels");
    if (!list) return "no channel list";
    std::vector<Channel> channels = channelsOf(list->value);
    if (channels.empty()) return "empty channel list";
    const size_t index = random.below(channels.size());
    std::string what;
    switch (random.below(6)) {
        case 0: {
            const int64_t types[] = {0, 1, 2, 3, -1, 255};
            const int64_t type = types[random.below(std::size(types))];
            putLE(channels[index].fields, 0, 4, uint64_t(type));
            what = "channel " + channels[index].name + " pixel type -> " + std::to_string(type);
            break;
        }
        case 1: {
            const int64_t samplings[] = {0, 2, 3, -1, 0x7FFFFFFF};
            const int64_t sampling = samplings[random.below(std::size(samplings))];
            putLE(channels[index].fields, random.percent(50) ? 8 : 12, 4, uint64_t(sampling));
            what = "channel " + channels[index].name + " sampling -> " + std::to_string(sampling);
            break;
        }
        case 2:
            what = "channel " + channels[index].name + " removed";
            channels.erase(channels.begin() + long(index));
            break;
        case 3:
            channels.insert(channels.begin() + long(random.below(channels.size())), channels[index]);
            what = "channel " + channels[index].name + " twice";
            break;
        case 4: {
            const std::string names[] = {"", "A", "Z", "R", std::string(40, 'n'), std::string(300, 'n')};
            channels[index].name = names[random.below(std::size(names))];
            what = "channel renamed to a name of " + std::to_string(channels[index].name.size()) + " characters";
            break;
        }
        default: {
            channels.push_back({"Q", le(4, random.below(3)) + std::string(4, '\0') + le(4, 1) + le(4, 1)});
            what = "channel added";
        }
    }
    list->value = channelListOf(channels);
    return what;
}

std::string damagePixelFormat(Exr& exr, Random& random) {
    switch (random.below(3)) {
        case 0: return damageChannels(exr, random);
        case 1: {
            Attribute* compression = exr.find("compression");
            if (!compression || compression->value.empty()) return "no compression";
            const int values[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 255};
            const int old = uint8_t(compression->value[0]), value = values[random.below(std::size(values))];
            compression->value[0] = char(value);
            return "compression " + std::to_string(old) + " -> " + std::to_string(value);
        }
        default: {
            // Version flags: tiled, long names, deep (non-image), multi-part; or another version.
            const uint32_t flags[] = {0x200, 0x400, 0x800, 0x1000};
            if (random.percent(25)) {
                exr.version = (exr.version & ~0xFFu) | uint32_t(random.percent(50) ? 1 : random.between(3, 255));
                return "version number -> " + std::to_string(exr.version & 0xFF);
            }
            const uint32_t flag = flags[random.below(std::size(flags))];
            exr.version ^= flag;
            return "version flag " + std::to_string(flag) + " toggled";
        }
    }
}

std::string floatBytes(float value) {
    uint32_t bits;
    std::memcpy(&bits, &value, 4);
    return le(4, bits);
}

std::string damageAttributes(Exr& exr, Random& random) {
    const size_t index = random.below(exr.attributes.size());
    Attribute& attribute = exr.attributes[index];
    switch (random.below(7)) {
        case 0: {
            Attribute* order = exr.find("lineOrder");
            if (!order || order->value.empty()) return "no lineOrder";
            const int values[] = {0, 1, 2, 3, 255};
            order->value[0] = char(values[random.below(std::size(values))]);
            return "lineOrder -> " + std::to_string(uint8_t(order->value[0]));
        }
        case 1: {
            const std::string types[] = {"box2f", "int",         "string", "chlist",
                                         "v2f",   "compression", "",       std::string(300, 't')};
            const std::string old = attribute.type;
            attribute.type = types[random.below(std::size(types))];
            return attribute.name + " type " + old + " -> " + attribute.type.substr(0, 20);
        }
        case 2: {
            const std::string name = attribute.name;
            exr.attributes.erase(exr.attributes.begin() + long(index));
            return "removed " + name;
        }
        case 3: {
            Attribute* tiles = exr.find("tiles");
            if (!tiles || tiles->value.size() < 9) {
                // chunkCount, which OIIO and OpenEXR check against the table.
                exr.attributes.push_back(
                    {"chunkCount", "int", le(4, interestingValue(random, exr.offsets.size(), 32))});
                return "added chunkCount " + std::to_string(getLE(exr.attributes.back().value, 0, 4));
            }
            const uint32_t old_x = getLE(tiles->value, 0, 4);
            if (random.percent(70)) {
                const uint64_t size = interestingValue(random, old_x, 32);
                putLE(tiles->value, random.percent(50) ? 0 : 4, 4, size);
                return "tile size -> " + std::to_string(size);
            }
            const uint8_t modes[] = {0x01, 0x02, 0x03, 0x10, 0x12, 0xFF};
            tiles->value[8] = char(modes[random.below(std::size(modes))]);
            return "tile level mode -> " + std::to_string(uint8_t(tiles->value[8]));
        }
        case 4: {
            const float values[] = {0.0f, -1.0f, NAN, INFINITY, 1e30f};
            const float value = values[random.below(std::size(values))];
            Attribute* target = exr.find(random.percent(50) ? "pixelAspectRatio" : "screenWindowWidth");
            if (!target) return "no pixelAspectRatio";
            target->value = floatBytes(value);
            return target->name + " -> " + std::to_string(value);
        }
        case 5: {
            const Attribute copy = attribute;
            exr.attributes.push_back(copy);
            if (copy.type == "box2i" && copy.value.size() == 16)
                putLE(exr.attributes.back().value, 8, 4, interestingValue(random, 10, 31));
            return copy.name + " twice";
        }
        default: {
            const std::string names[] = {std::string(32, 'a'), std::string(255, 'b'), "comments", "owner"};
            exr.attributes.push_back({names[random.below(std::size(names))], random.percent(50) ? "string" : "fuzzType",
                                      random.bytes(random.below(64))});
            return "added attribute " + exr.attributes.back().name.substr(0, 10) + " of type " +
                   exr.attributes.back().type;
        }
    }
}

// Where each chunk begins in exr.chunks.
std::vector<size_t> chunkStarts(const Exr& exr) {
    std::vector<size_t> starts;
    for (uint64_t offset : exr.offsets)
        if (offset >= exr.original_chunks_at && offset - exr.original_chunks_at < exr.chunks.size())
            starts.push_back(size_t(offset - exr.original_chunks_at));
    return starts;
}

std::string damageOffsets(Exr& exr, Random& random) {
    if (exr.offsets.empty()) return "no offset table";
    const size_t index = random.below(exr.offsets.size());
    const uint64_t old = exr.offsets[index];
    const uint64_t end = exr.original_chunks_at + exr.chunks.size();
    const uint64_t values[] = {0,
                               8,
                               old + 1,
                               old - 1,
                               end,
                               end + 1000,
                               exr.offsets[random.below(exr.offsets.size())],
                               uint64_t(-1),
                               uint64_t(1) << 63};
    exr.offsets[index] = values[random.below(std::size(values))];
    return "offset table entry " + std::to_string(index) + " " + std::to_string(old) + " -> " +
           std::to_string(exr.offsets[index]);
}

std::string damageStream(Exr& exr, Random& random) {
    const std::vector<size_t> starts = chunkStarts(exr);
    if (starts.empty()) return "no chunks";
    const size_t start = random.pick(starts);
    const bool tiled = exr.find("tiles") != nullptr;
    const size_t size_at = start + (tiled ? 16 : 4);
    switch (random.below(4)) {
        case 0: {
            const int32_t old = int32_t(getLE(exr.chunks, size_at, 4));
            const int64_t value = interestingSigned(random, old, 32);
            putLE(exr.chunks, size_at, 4, uint64_t(value));
            return "chunk data size " + std::to_string(old) + " -> " + std::to_string(value);
        }
        case 1: {
            const size_t field = tiled ? random.below(4) : 0;
            const int32_t old = int32_t(getLE(exr.chunks, start + field * 4, 4));
            const int64_t value = interestingSigned(random, old, 32);
            putLE(exr.chunks, start + field * 4, 4, uint64_t(value));
            return std::string(tiled ? "tile coordinate " : "chunk y ") + std::to_string(old) + " -> " +
                   std::to_string(value);
        }
        default: {
            const size_t data = size_at + 4;
            if (data >= exr.chunks.size()) return "chunk without data";
            const size_t length = std::min<size_t>(getLE(exr.chunks, size_at, 4), exr.chunks.size() - data);
            const size_t at = data + random.below(std::max<size_t>(1, length)),
                         count = std::min<size_t>(exr.chunks.size() - at, random.between(1, 16));
            exr.chunks.replace(at, count, random.bytes(count));
            return std::to_string(count) + " random bytes in chunk data";
        }
    }
}

// An attribute's size field lies; the file is written with it as is.
std::string lieAboutSize(const Exr& exr, std::string& file, Random& random) {
    file = fileOf(exr);
    const size_t index = random.below(exr.attributes.size());
    size_t at = 8;
    for (size_t i = 0; i < index; ++i) {
        const Attribute& a = exr.attributes[i];
        at += a.name.size() + a.type.size() + 6 + a.value.size();
    }
    const Attribute& a = exr.attributes[index];
    const uint64_t size = interestingValue(random, a.value.size(), 32);
    putLE(file, at + a.name.size() + a.type.size() + 2, 4, size);
    return a.name + " size " + std::to_string(a.value.size()) + " -> " + std::to_string(size);
}

}  // namespace

std::string damageExr(std::string& file, DamageKind kind, Random& random) {
    std::optional<Exr> exr = parseExr(file);
    if (!exr || exr->attributes.empty()) return "not an EXR";
    std::string what;
    switch (kind) {
        case DamageKind::Size: what = damageWindow(*exr, random); break;
        case DamageKind::PixelFormat: what = damagePixelFormat(*exr, random); break;
        case DamageKind::Structure:
            if (random.percent(20)) return lieAboutSize(*exr, file, random);
            what = random.percent(30) ? damageOffsets(*exr, random) : damageAttributes(*exr, random);
            break;
        default: what = damageStream(*exr, random); break;
    }
    file = fileOf(*exr);
    return what;
}

}  // namespace fuzz
