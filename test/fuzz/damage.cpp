#include "damage.h"

#include <algorithm>

#include "formats.h"

namespace fuzz {

namespace {

std::string truncate(std::string& file, Random& random) {
    size_t keep;
    switch (random.below(3)) {
        case 0: keep = random.below(std::min<size_t>(file.size(), 128)); break;  // inside the header
        case 1: keep = random.below(file.size()); break;
        default: keep = file.size() - std::min<size_t>(file.size(), size_t(random.between(1, 8))); break;
    }
    const std::string what = "cut from " + std::to_string(file.size()) + " to " + std::to_string(keep) + " bytes";
    file.resize(keep);
    return what;
}

// Flips land in the first 256 bytes half the time: that is where the headers are.
std::string flipBits(const Format& format, std::string& file, Random& random) {
    if (file.size() <= format.signature_size) return "nothing to flip";
    const size_t body = file.size() - format.signature_size;
    const int flips = int(random.between(1, 8));
    std::string what = "flipped bits at";
    for (int i = 0; i < flips; ++i) {
        const size_t span = random.percent(50) ? std::min<size_t>(body, 256) : body;
        const size_t at = format.signature_size + random.below(span);
        const int bit = int(random.below(8));
        file[at] = char(uint8_t(file[at]) ^ (1u << bit));
        what += ' ' + std::to_string(at) + '.' + std::to_string(bit);
    }
    return what;
}

std::string randomBody(const Format& format, std::string& file, Random& random) {
    const size_t length = random.below(file.size() * 2 + 1);
    file = file.substr(0, format.signature_size) + random.bytes(length);
    return std::to_string(length) + " random bytes after the " + std::to_string(format.signature_size) +
           "-byte signature";
}

}  // namespace

const char* damageKindName(DamageKind kind) {
    switch (kind) {
        case DamageKind::Truncate: return "truncate";
        case DamageKind::BitFlip: return "bit-flip";
        case DamageKind::RandomBody: return "random-body";
        case DamageKind::Size: return "size";
        case DamageKind::PixelFormat: return "pixel-format";
        case DamageKind::Structure: return "structure";
        case DamageKind::Stream: return "stream";
    }
    return "?";
}

std::string damageFile(const Format& format, DamageKind kind, std::string& file, Random& random) {
    switch (kind) {
        case DamageKind::Truncate: return truncate(file, random);
        case DamageKind::BitFlip:
        case DamageKind::RandomBody: {
            std::string what =
                kind == DamageKind::BitFlip ? flipBits(format, file, random) : randomBody(format, file, random);
            if (format.repair) format.repair(file);
            return what;
        }
        default: {
            std::string what = format.damage(file, kind, random);
            // Now and then a second one: some faults show only in combination. Not of sizes:
            // two large sides make an image of many megapixels which, where the format lets
            // the data end early (RLE), decodes and keeps ddtup busy for minutes.
            if (kind != DamageKind::Size && random.percent(25)) what += "; " + format.damage(file, kind, random);
            return what;
        }
    }
}

}  // namespace fuzz
