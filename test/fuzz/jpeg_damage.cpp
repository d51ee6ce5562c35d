// JPEG: the file is taken apart into marker segments (and each scan's entropy-coded data),
// a segment is changed, and the file is put together with the lengths right unless the
// damage is the length. JPEG has no checksums.
#include <algorithm>

#include "bytes.h"
#include "formats.h"
#include "interesting.h"
#include "tiff_directory.h"

namespace fuzz {

namespace {

constexpr uint8_t kSOI = 0xD8, kEOI = 0xD9, kSOS = 0xDA, kDQT = 0xDB, kDHT = 0xC4, kDRI = 0xDD, kAPP1 = 0xE1,
                  kAPP2 = 0xE2;

struct Segment {
    uint8_t marker;
    std::string payload;  // after the length field
    std::string scan;     // the entropy-coded data after an SOS, restart markers included
};

bool hasLength(uint8_t marker) {
    return !(marker == kSOI || marker == kEOI || (marker >= 0xD0 && marker <= 0xD7) || marker == 0x01);
}
bool isFrame(uint8_t marker) {
    return marker >= 0xC0 && marker <= 0xCF && marker != kDHT && marker != 0xC8 && marker != 0xCC;
}

std::vector<Segment> segmentsOf(const std::string& file) {
    std::vector<Segment> segments;
    size_t at = 2;
    while (at + 2 <= file.size() && uint8_t(file[at]) == 0xFF) {
        const uint8_t marker = uint8_t(file[at + 1]);
        if (marker == 0xFF) {
            ++at;
            continue;
        }
        Segment segment{marker, "", ""};
        at += 2;
        if (hasLength(marker)) {
            const uint32_t length = getBE(file, at, 2);
            if (length < 2 || at + length > file.size()) break;
            segment.payload = file.substr(at + 2, length - 2);
            at += length;
        }
        if (marker == kSOS) {
            size_t end = at;
            while (end + 1 < file.size() && !(uint8_t(file[end]) == 0xFF && file[end + 1] != 0 &&
                                              (uint8_t(file[end + 1]) < 0xD0 || uint8_t(file[end + 1]) > 0xD7)))
                ++end;
            segment.scan = file.substr(at, end - at);
            at = end;
        }
        segments.push_back(segment);
        if (marker == kEOI) break;
    }
    return segments;
}

std::string fileOf(const std::vector<Segment>& segments) {
    std::string file = "\xFF\xD8";
    for (const Segment& s : segments) {
        file += '\xFF';
        file += char(s.marker);
        if (hasLength(s.marker)) file += be(2, s.payload.size() + 2) + s.payload;
        file += s.scan;
    }
    return file;
}

Segment* findFirst(std::vector<Segment>& segments, bool (*matches)(uint8_t)) {
    for (Segment& s : segments)
        if (matches(s.marker)) return &s;
    return nullptr;
}

std::vector<Segment*> all(std::vector<Segment>& segments, uint8_t marker) {
    std::vector<Segment*> found;
    for (Segment& s : segments)
        if (s.marker == marker) found.push_back(&s);
    return found;
}

std::string hex(uint32_t value) {
    const char digits[] = "0123456789ABCDEF";
    return std::string("0x") + digits[(value >> 4) & 15] + digits[value & 15];
}

std::string damageSize(std::vector<Segment>& segments, Random& random) {
    Segment* frame = findFirst(segments, isFrame);
    if (!frame || frame->payload.size() < 5) return "no frame header";
    const uint32_t height = getBE(frame->payload, 1, 2), width = getBE(frame->payload, 3, 2);
    switch (random.below(3)) {
        case 0: {
            const uint64_t value = interestingValue(random, height, 16);
            putBE(frame->payload, 1, 2, value);
            return "SOF height " + std::to_string(height) + " -> " + std::to_string(value);
        }
        case 1: {
            const uint64_t value = interestingValue(random, width, 16);
            putBE(frame->payload, 3, 2, value);
            return "SOF width " + std::to_string(width) + " -> " + std::to_string(value);
        }
        default:
            putBE(frame->payload, 1, 2, width);
            putBE(frame->payload, 3, 2, height);
            return "SOF width and height swapped";
    }
}

std::string damagePixelFormat(std::vector<Segment>& segments, Random& random) {
    Segment* frame = findFirst(segments, isFrame);
    if (!frame || frame->payload.size() < 6) return "no frame header";
    std::string& sof = frame->payload;
    const size_t components = uint8_t(sof[5]);
    const size_t component = components ? 6 + 3 * random.below(components) : 6;
    switch (random.below(6)) {
        case 0: {
            const int precisions[] = {0, 1, 2, 7, 9, 12, 16, 255};
            const int value = precisions[random.below(std::size(precisions))];
            sof[0] = char(value);
            return "SOF precision -> " + std::to_string(value);
        }
        case 1: {
            const int counts[] = {0, 1, 2, 3, 4, 5, 255};
            const int count = counts[random.below(std::size(counts))];
            sof[5] = char(count);
            if (random.percent(60)) {
                // The component list resized to match, new entries copied from the first.
                const std::string first = sof.size() >= 9 ? sof.substr(6, 3) : std::string("\1\x11\0", 3);
                sof.resize(6);
                for (int i = 0; i < count; ++i) sof += std::string{char(i + 1), first[1], first[2]};
                return "SOF component count -> " + std::to_string(count) + " with as many entries";
            }
            return "SOF component count " + std::to_string(components) + " -> " + std::to_string(count);
        }
        case 2: {
            const uint8_t factors[] = {0x00, 0x01, 0x10, 0x12, 0x21, 0x22, 0x14, 0x41,
                                       0x44, 0x33, 0x1F, 0xF1, 0xFF, 0x24, 0x42};
            const uint8_t value = factors[random.below(std::size(factors))];
            putBE(sof, component + 1, 1, value);
            return "SOF component " + std::to_string((component - 6) / 3) + " sampling -> " + hex(value);
        }
        case 3: {
            const int tables[] = {1, 2, 3, 4, 15, 255};
            const int value = tables[random.below(std::size(tables))];
            putBE(sof, component + 2, 1, uint64_t(value));
            return "SOF component " + std::to_string((component - 6) / 3) + " quantisation table -> " +
                   std::to_string(value);
        }
        case 4: {
            const int value = random.percent(50) ? 1 : int(random.below(256));
            putBE(sof, component, 1, uint64_t(value));
            return "SOF component " + std::to_string((component - 6) / 3) + " id -> " + std::to_string(value);
        }
        default: {
            const uint8_t types[] = {0xC0, 0xC1, 0xC2, 0xC3, 0xC5, 0xC6, 0xC7, 0xC9, 0xCA, 0xCB, 0xCD, 0xCE, 0xCF};
            const uint8_t type = types[random.below(std::size(types))];
            const uint8_t old = frame->marker;
            frame->marker = type;
            return "frame type " + hex(old) + " -> " + hex(type);
        }
    }
}

std::string damageTables(std::vector<Segment>& segments, Random& random) {
    if (random.percent(50)) {
        std::vector<Segment*> tables = all(segments, kDHT);
        if (tables.empty()) return "no DHT";
        std::string& dht = random.pick(tables)->payload;
        if (dht.size() < 17) return "DHT too short";
        switch (random.below(4)) {
            case 0: {
                const uint8_t classes[] = {0x02, 0x04, 0x14, 0x20, 0x1F, 0xFF};
                dht[0] = char(classes[random.below(std::size(classes))]);
                return "DHT class/id -> " + hex(uint8_t(dht[0]));
            }
            case 1: {
                // More codes of a length than the length allows, or codes that add up wrong.
                const size_t length = 1 + random.below(16);
                const uint64_t count =
                    random.percent(50) ? random.between(3, 255) : interestingValue(random, uint8_t(dht[length]), 8);
                dht[length] = char(count);
                return "DHT count of " + std::to_string(length) + "-bit codes -> " + std::to_string(count);
            }
            case 2: std::fill(dht.begin() + 1, dht.begin() + 17, '\0'); return "DHT with no codes";
            default: {
                const size_t at = 17 + random.below(std::max<size_t>(1, dht.size() - 17));
                if (at < dht.size()) dht[at] = char(random.percent(50) ? 0xFF : random.byte());
                return "DHT symbol at " + std::to_string(at) + " set";
            }
        }
    }
    std::vector<Segment*> tables = all(segments, kDQT);
    if (tables.empty()) return "no DQT";
    std::string& dqt = random.pick(tables)->payload;
    if (dqt.empty()) return "DQT empty";
    switch (random.below(3)) {
        case 0: {
            const uint8_t values[] = {0x10, 0x04, 0x05, 0x0F, 0x20, 0xFF};
            dqt[0] = char(values[random.below(std::size(values))]);
            return "DQT precision/id -> " + hex(uint8_t(dqt[0]));
        }
        case 1: std::fill(dqt.begin() + 1, dqt.end(), '\0'); return "DQT of zeros";
        default: {
            const size_t size = random.below(dqt.size());
            dqt.resize(size);
            return "DQT cut to " + std::to_string(size) + " bytes";
        }
    }
}

std::string damageScanHeader(std::vector<Segment>& segments, Random& random) {
    std::vector<Segment*> scans = all(segments, kSOS);
    if (scans.empty()) return "no SOS";
    std::string& sos = random.pick(scans)->payload;
    if (sos.size() < 4) return "SOS too short";
    const size_t components = uint8_t(sos[0]);
    switch (random.below(4)) {
        case 0: {
            const int counts[] = {0, 2, 4, 5, 255};
            sos[0] = char(counts[random.below(std::size(counts))]);
            return "SOS component count " + std::to_string(components) + " -> " + std::to_string(uint8_t(sos[0]));
        }
        case 1: {
            const size_t at = 1 + 2 * random.below(std::max<size_t>(1, components));
            putBE(sos, at, 1, random.percent(50) ? random.between(4, 9) : random.byte());
            return "SOS component selector -> " + std::to_string(getBE(sos, at, 1));
        }
        case 2: {
            const size_t at = 2 + 2 * random.below(std::max<size_t>(1, components));
            putBE(sos, at, 1, random.byte());
            return "SOS table selectors -> " + hex(getBE(sos, at, 1));
        }
        default: {
            // Spectral selection and successive approximation (progressive scans).
            const size_t at = sos.size() - 3 + random.below(3);
            putBE(sos, at, 1, random.percent(50) ? random.below(64) : random.byte());
            return "SOS Ss/Se/Ah-Al byte -> " + std::to_string(getBE(sos, at, 1));
        }
    }
}

// A segment's length field lies; the file is written with it as is.
std::string lieAboutLength(const std::vector<Segment>& segments, std::string& file, Random& random) {
    file = fileOf(segments);
    std::vector<size_t> with_length;
    for (size_t i = 0; i < segments.size(); ++i)
        if (hasLength(segments[i].marker)) with_length.push_back(i);
    if (with_length.empty()) return "no segment with a length";
    const size_t index = random.pick(with_length);
    size_t at = 2;
    for (size_t i = 0; i < index; ++i)
        at += 2 + (hasLength(segments[i].marker) ? 2 + segments[i].payload.size() : 0) + segments[i].scan.size();
    const uint64_t length = interestingValue(random, segments[index].payload.size() + 2, 16);
    putBE(file, at + 2, 2, length);
    return "marker " + hex(segments[index].marker) + " length -> " + std::to_string(length);
}

std::string damageStructure(std::vector<Segment>& segments, Random& random) {
    if (segments.empty()) return "no segments";
    switch (random.below(7)) {
        case 0: return damageTables(segments, random);
        case 1: return damageScanHeader(segments, random);
        case 2: {
            const size_t index = random.below(segments.size());
            const uint8_t marker = segments[index].marker;
            segments.erase(segments.begin() + long(index));
            return "removed marker " + hex(marker);
        }
        case 3: {
            const Segment copy = random.pick(segments);
            segments.insert(segments.begin() + long(random.below(segments.size())), copy);
            return "duplicated marker " + hex(copy.marker);
        }
        case 4: {
            const uint64_t interval = random.percent(50) ? random.between(1, 8) : interestingValue(random, 1, 16);
            segments.insert(segments.begin(), Segment{kDRI, be(2, interval), ""});
            return "restart interval " + std::to_string(interval) + " without restart markers";
        }
        case 5: {
            // EXIF: OIIO parses it itself. Damage the one there, or add a damaged one.
            for (Segment& s : segments)
                if (s.marker == kAPP1 && s.payload.compare(0, 6, std::string("Exif\0\0", 6)) == 0) {
                    std::string tiff = s.payload.substr(6);
                    const std::string what = damageTiffStructure(tiff, random);
                    s.payload = s.payload.substr(0, 6) + tiff;
                    return "EXIF " + what;
                }
            std::string tiff = makeExifBlock(random);
            const std::string what = damageTiffStructure(tiff, random);
            segments.insert(segments.begin(), Segment{kAPP1, std::string("Exif\0\0", 6) + tiff, ""});
            return "added EXIF, " + what;
        }
        default: {
            // ICC profile pieces numbered wrongly.
            const uint8_t sequence = uint8_t(random.below(4)), count = uint8_t(random.below(3));
            segments.insert(segments.begin(), Segment{kAPP2,
                                                      std::string("ICC_PROFILE\0", 12) + char(sequence) + char(count) +
                                                          random.bytes(random.below(200)),
                                                      ""});
            return "ICC piece " + std::to_string(sequence) + " of " + std::to_string(count);
        }
    }
}

// Bytes of entropy-coded data, with a 0xFF stuffed as the format requires.
std::string codedBytes(Random& random, size_t count) {
    std::string out;
    for (size_t i = 0; i < count; ++i) {
        out += char(random.byte());
        if (uint8_t(out.back()) == 0xFF) out += '\0';
    }
    return out;
}

std::string damageStream(std::vector<Segment>& segments, Random& random) {
    std::vector<size_t> scans;
    for (size_t i = 0; i < segments.size(); ++i)
        if (segments[i].marker == kSOS) scans.push_back(i);
    if (scans.empty()) return "no scans";
    const size_t index = random.pick(scans);
    std::string& data = segments[index].scan;
    const size_t at = random.below(data.size() + 1);
    // Removing and reordering scans needs a progressive file (several scans).
    switch (random.below(scans.size() > 1 ? 6 : 4)) {
        case 0: {
            const size_t count = std::min<size_t>(data.size() - at, random.between(1, 32));
            data.replace(at, count, codedBytes(random, count));
            return std::to_string(count) + " random bytes in scan data at " + std::to_string(at);
        }
        case 1: data.resize(at); return "scan data cut to " + std::to_string(at) + " bytes";
        case 2: {
            const uint8_t marker = uint8_t(0xD0 + random.below(8));
            data.insert(at, std::string{'\xFF', char(marker)});
            return "restart marker " + hex(marker) + " inside scan data";
        }
        case 3:
            data.insert(at, codedBytes(random, random.between(1, 2000)));
            return "random bytes inserted in scan data";
        case 4: {
            segments.erase(segments.begin() + long(index));
            return "progressive scan " + std::to_string(index) + " removed";
        }
        default: {
            const size_t other = random.pick(scans);
            std::swap(segments[index], segments[other]);
            return "progressive scans swapped";
        }
    }
}

}  // namespace

std::string damageJpeg(std::string& file, DamageKind kind, Random& random) {
    std::vector<Segment> segments = segmentsOf(file);
    std::string what;
    switch (kind) {
        case DamageKind::Size: what = damageSize(segments, random); break;
        case DamageKind::PixelFormat: what = damagePixelFormat(segments, random); break;
        case DamageKind::Structure:
            if (random.percent(20)) return lieAboutLength(segments, file, random);
            what = damageStructure(segments, random);
            break;
        default: what = damageStream(segments, random); break;
    }
    file = fileOf(segments);
    return what;
}

}  // namespace fuzz
