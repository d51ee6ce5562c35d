// WebP: the RIFF container is taken apart into chunks (VP8X, ALPH, VP8, VP8L, …); the
// chunk headers and the bitstream headers inside are changed and the container put together
// with the sizes right unless a size is the damage. WebP has no checksums.
#include <algorithm>

#include "bytes.h"
#include "formats.h"
#include "interesting.h"
#include "tiff_directory.h"

namespace fuzz {

namespace {

struct Chunk {
    std::string fourcc, data;
};

std::vector<Chunk> chunksOf(const std::string& file) {
    std::vector<Chunk> chunks;
    for (size_t at = 12; at + 8 <= file.size();) {
        const uint32_t size = getLE(file, at + 4, 4);
        if (size > file.size() - at - 8) break;
        chunks.push_back({file.substr(at, 4), file.substr(at + 8, size)});
        at += 8 + size + (size & 1);
    }
    return chunks;
}

std::string chunkBytes(const Chunk& chunk) {
    return chunk.fourcc + le(4, chunk.data.size()) + chunk.data + (chunk.data.size() & 1 ? std::string(1, '\0') : "");
}

std::string fileOf(const std::vector<Chunk>& chunks) {
    std::string body = "WEBP";
    for (const Chunk& chunk : chunks) body += chunkBytes(chunk);
    return "RIFF" + le(4, body.size()) + body;
}

Chunk* find(std::vector<Chunk>& chunks, const std::string& fourcc) {
    for (Chunk& c : chunks)
        if (c.fourcc == fourcc) return &c;
    return nullptr;
}

// The VP8X header a file with these chunks needs, canvas from the image chunk.
Chunk* ensureVp8x(std::vector<Chunk>& chunks) {
    if (Chunk* vp8x = find(chunks, "VP8X")) return vp8x;
    chunks.insert(chunks.begin(), Chunk{"VP8X", std::string(4, '\0') + le(3, 15) + le(3, 15)});
    return &chunks.front();
}

std::string damageSize(std::vector<Chunk>& chunks, Random& random) {
    std::vector<std::string> present;
    for (const char* fourcc : {"VP8 ", "VP8L", "VP8X"})
        if (find(chunks, fourcc)) present.push_back(fourcc);
    if (present.empty()) return "no image chunk";
    const std::string fourcc = random.pick(present);
    Chunk& chunk = *find(chunks, fourcc);
    const bool height = random.percent(50);
    if (fourcc == "VP8 ") {
        // After the 3-byte frame tag and the start code: 14 bits of size, 2 of scaling.
        const size_t at = height ? 8 : 6;
        const uint32_t old = getLE(chunk.data, at, 2);
        const uint64_t value = random.percent(20) ? (old & 0x3FFF) | uint64_t(random.below(4)) << 14
                                                  : interestingValue(random, old & 0x3FFF, 14);
        putLE(chunk.data, at, 2, value);
        return std::string("VP8 ") + (height ? "height" : "width") + " field " + std::to_string(old) + " -> " +
               std::to_string(value);
    }
    if (fourcc == "VP8L") {
        // After the signature byte: width − 1 and height − 1 in 14 bits each.
        uint32_t bits = getLE(chunk.data, 1, 4);
        const int shift = height ? 14 : 0;
        const uint32_t old = (bits >> shift) & 0x3FFF;
        const uint64_t value = interestingValue(random, old, 14);
        bits = (bits & ~(0x3FFFu << shift)) | uint32_t(value) << shift;
        putLE(chunk.data, 1, 4, bits);
        return std::string("VP8L ") + (height ? "height" : "width") + " − 1 " + std::to_string(old) + " -> " +
               std::to_string(value);
    }
    const size_t at = height ? 7 : 4;
    const uint32_t old = getLE(chunk.data, at, 3);
    const uint64_t value = interestingValue(random, old, 24);
    putLE(chunk.data, at, 3, value);
    return std::string("VP8X canvas ") + (height ? "height" : "width") + " − 1 " + std::to_string(old) + " -> " +
           std::to_string(value);
}

std::string damagePixelFormat(std::vector<Chunk>& chunks, Random& random) {
    switch (random.below(4)) {
        case 0: {
            Chunk* vp8x = ensureVp8x(chunks);
            const uint8_t flags[] = {0x02, 0x04, 0x08, 0x10, 0x20, 0x01, 0xC0};
            const uint8_t flag = flags[random.below(std::size(flags))];
            vp8x->data[0] = char(uint8_t(vp8x->data[0]) ^ flag);
            return "VP8X flag " + std::to_string(flag) + " toggled";
        }
        case 1: {
            Chunk* vp8l = find(chunks, "VP8L");
            if (!vp8l || vp8l->data.size() < 5) return "no VP8L";
            // The alpha hint and the 3-bit version after the sizes, or the signature byte.
            if (random.percent(30)) {
                vp8l->data[0] = char(random.byte());
                return "VP8L signature byte -> " + std::to_string(uint8_t(vp8l->data[0]));
            }
            vp8l->data[4] = char(uint8_t(vp8l->data[4]) ^ (0x10 << random.below(4)));
            return "VP8L alpha/version bits changed";
        }
        case 2: {
            Chunk* vp8 = find(chunks, "VP8 ");
            if (!vp8 || vp8->data.size() < 10) return "no VP8";
            // Frame tag: key frame bit (0 = key frame), 3-bit version, show-frame bit.
            const uint8_t masks[] = {0x01, 0x02, 0x04, 0x08, 0x0E, 0x10};
            vp8->data[0] = char(uint8_t(vp8->data[0]) ^ masks[random.below(std::size(masks))]);
            if (random.percent(30)) vp8->data[3 + random.below(3)] = char(random.byte());  // the start code
            return "VP8 frame tag changed";
        }
        default: {
            Chunk* alph = find(chunks, "ALPH");
            if (!alph || alph->data.empty()) return "no ALPH";
            alph->data[0] = char(random.byte());
            return "ALPH header -> " + std::to_string(uint8_t(alph->data[0]));
        }
    }
}

// An animation: ANIM and the image inside an ANMF frame with damaged placement.
void makeAnimated(std::vector<Chunk>& chunks, Random& random) {
    Chunk* vp8x = ensureVp8x(chunks);
    vp8x->data[0] = char(uint8_t(vp8x->data[0]) | 0x02);
    std::string frames;
    for (Chunk& chunk : chunks)
        if (chunk.fourcc == "VP8 " || chunk.fourcc == "VP8L" || chunk.fourcc == "ALPH") frames += chunkBytes(chunk);
    std::erase_if(chunks,
                  [](const Chunk& c) { return c.fourcc == "VP8 " || c.fourcc == "VP8L" || c.fourcc == "ALPH"; });
    const uint32_t width = getLE(find(chunks, "VP8X")->data, 4, 3), height = getLE(find(chunks, "VP8X")->data, 7, 3);
    chunks.push_back({"ANIM", le(4, 0) + le(2, 0)});
    for (int frame = 0, count = int(random.between(1, 3)); frame < count; ++frame) {
        const std::string placement = le(3, random.percent(60) ? 0 : interestingValue(random, 0, 24)) +
                                      le(3, random.percent(60) ? 0 : interestingValue(random, 0, 24)) +
                                      le(3, random.percent(60) ? width : interestingValue(random, width, 24)) +
                                      le(3, random.percent(60) ? height : interestingValue(random, height, 24)) +
                                      le(3, 100) + char(random.below(4));
        chunks.push_back({"ANMF", placement + frames});
    }
}

// The RIFF size or a chunk's size lies; the file is written with it as is.
std::string lieAboutSize(const std::vector<Chunk>& chunks, std::string& file, Random& random) {
    file = fileOf(chunks);
    if (chunks.empty() || random.percent(30)) {
        const uint64_t size = interestingValue(random, getLE(file, 4, 4), 32);
        putLE(file, 4, 4, size);
        return "RIFF size -> " + std::to_string(size);
    }
    const size_t index = random.below(chunks.size());
    size_t at = 12;
    for (size_t i = 0; i < index; ++i) at += chunkBytes(chunks[i]).size();
    const uint64_t size = interestingValue(random, chunks[index].data.size(), 32);
    putLE(file, at + 4, 4, size);
    return chunks[index].fourcc + " size " + std::to_string(chunks[index].data.size()) + " -> " + std::to_string(size);
}

std::string damageStructure(std::vector<Chunk>& chunks, Random& random) {
    switch (random.below(5)) {
        case 0: {
            if (chunks.empty()) return "no chunks";
            const size_t index = random.below(chunks.size());
            const std::string fourcc = chunks[index].fourcc;
            chunks.erase(chunks.begin() + long(index));
            return "removed " + fourcc;
        }
        case 1: {
            if (chunks.size() < 2) return "one chunk";
            const size_t a = random.below(chunks.size()), b = random.below(chunks.size());
            std::swap(chunks[a], chunks[b]);
            return "swapped " + chunks[a].fourcc + " and " + chunks[b].fourcc;
        }
        case 2: makeAnimated(chunks, random); return "made an animation with damaged frame placement";
        case 3: {
            // EXIF, which OIIO hands to its own parser past a 6-byte "Exif\0\0" prefix.
            Chunk* vp8x = ensureVp8x(chunks);
            vp8x->data[0] = char(uint8_t(vp8x->data[0]) | 0x08);
            std::string exif;
            if (random.percent(40)) {
                exif = random.bytes(random.below(8));
            } else {
                exif = makeExifBlock(random);
                damageTiffStructure(exif, random);
                exif = std::string("Exif\0\0", 6) + exif;
            }
            chunks.push_back({"EXIF", exif});
            return "EXIF chunk of " + std::to_string(exif.size()) + " bytes";
        }
        default: {
            const std::string fourccs[] = {"ICCP", "XMP ", "ALPH", "VP8 ", "VP8L", "VP8X"};
            const std::string fourcc = fourccs[random.below(std::size(fourccs))];
            chunks.insert(chunks.begin() + long(random.below(chunks.size() + 1)),
                          Chunk{fourcc, random.bytes(random.below(64))});
            return "inserted " + fourcc + " of random bytes";
        }
    }
}

std::string damageStream(std::vector<Chunk>& chunks, Random& random) {
    std::vector<Chunk*> coded;
    for (Chunk& c : chunks)
        if (c.fourcc == "VP8 " || c.fourcc == "VP8L" || c.fourcc == "ALPH") coded.push_back(&c);
    if (coded.empty()) return "no coded data";
    Chunk& chunk = *random.pick(coded);
    if (chunk.fourcc == "VP8 " && random.percent(30)) {
        // The first partition's size: 19 bits of the frame tag.
        const uint32_t tag = getLE(chunk.data, 0, 3);
        const uint64_t size = interestingValue(random, tag >> 5, 19);
        putLE(chunk.data, 0, 3, (tag & 0x1F) | size << 5);
        return "VP8 first partition size -> " + std::to_string(size);
    }
    const size_t header = chunk.fourcc == "VP8 " ? 10 : chunk.fourcc == "VP8L" ? 5 : 1;
    if (chunk.data.size() <= header) return "coded data too short";
    const size_t at = header + random.below(chunk.data.size() - header),
                 count = std::min<size_t>(chunk.data.size() - at, random.between(1, 16));
    if (random.percent(30)) {
        chunk.data.resize(at);
        return chunk.fourcc + " data cut to " + std::to_string(at) + " bytes";
    }
    chunk.data.replace(at, count, random.bytes(count));
    return std::to_string(count) + " random bytes in " + chunk.fourcc + " data";
}

}  // namespace

std::string damageWebp(std::string& file, DamageKind kind, Random& random) {
    std::vector<Chunk> chunks = chunksOf(file);
    std::string what;
    switch (kind) {
        case DamageKind::Size: what = damageSize(chunks, random); break;
        case DamageKind::PixelFormat: what = damagePixelFormat(chunks, random); break;
        case DamageKind::Structure:
            if (random.percent(20)) return lieAboutSize(chunks, file, random);
            what = damageStructure(chunks, random);
            break;
        default: what = damageStream(chunks, random); break;
    }
    file = fileOf(chunks);
    return what;
}

}  // namespace fuzz
