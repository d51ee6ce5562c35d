// TIFF: entries of the first image's directory are changed in place (their 12-byte slots
// stay where they are), by tag: the fields libtiff and OIIO size buffers and loops by.
#include "bytes.h"
#include "formats.h"
#include "interesting.h"
#include "tiff_directory.h"

namespace fuzz {

namespace {

enum Tag : uint16_t {
    kImageWidth = 256, kImageLength = 257, kBitsPerSample = 258, kCompression = 259, kPhotometric = 262,
    kFillOrder = 266, kStripOffsets = 273, kOrientation = 274, kSamplesPerPixel = 277, kRowsPerStrip = 278,
    kStripByteCounts = 279, kPlanarConfig = 284, kPredictor = 317, kColorMap = 320, kTileWidth = 322,
    kTileLength = 323, kTileOffsets = 324, kTileByteCounts = 325, kExtraSamples = 338, kSampleFormat = 339,
    kJpegTables = 347, kExifIfd = 34665, kIccProfile = 34675,
};

// Sets every value of `tag` to one of `choices` (or an interesting value); a missing tag is
// made by re-tagging an entry nobody needs, which keeps the directory's layout.
std::string setTag(std::string& file, const TiffLayout& layout, uint16_t tag, const char* name,
                   const std::vector<uint64_t>& choices, Random& random) {
    const TiffEntry* entry = layout.find(tag);
    if (!entry) {
        for (uint16_t spare : {uint16_t(296), uint16_t(282), uint16_t(283), uint16_t(305), uint16_t(kPredictor)})
            if (const TiffEntry* other = layout.find(spare); other && spare != tag) {
                layout.put(file, other->at, 2, tag);
                layout.put(file, other->at + 2, 2, 3);  // SHORT
                layout.put(file, layout.countAt(*other), layout.offsetSize(), 1);
                const uint64_t value = random.pick(choices);
                layout.put(file, layout.valueAt(*other), layout.offsetSize(), 0);
                layout.put(file, layout.valueAt(*other), 2, value);
                return std::string("added ") + name + " = " + std::to_string(value);
            }
        return std::string("no ") + name + " and no spare entry";
    }
    const std::vector<uint32_t> values = layout.values(file, *entry);
    if (values.empty()) return std::string(name) + " has no readable values";
    const int bits = 8 * std::min(4, TiffLayout::typeSize(entry->type));
    const uint64_t value = random.percent(75) ? random.pick(choices) : interestingValue(random, values[0], bits);
    const bool every = random.percent(70);
    for (size_t i = 0; i < values.size(); ++i)
        if (every || i == 0) layout.setValue(file, *entry, i, value);
    return std::string(name) + (every ? "" : "[0]") + " " + std::to_string(values[0]) + " -> " + std::to_string(value);
}

std::string damageSize(std::string& file, const TiffLayout& layout, Random& random) {
    const uint16_t tag = random.percent(50) ? kImageWidth : kImageLength;
    const TiffEntry* entry = layout.find(tag);
    if (!entry) return "no image size";
    const uint32_t old = layout.values(file, *entry).empty() ? 0 : layout.values(file, *entry)[0];
    // As a LONG half the time, so the value may pass 65535.
    if (random.percent(50)) {
        layout.put(file, entry->at + 2, 2, 4);
        const uint64_t value = interestingValue(random, old, 32);
        layout.put(file, layout.valueAt(*entry), layout.offsetSize(), 0);
        layout.put(file, layout.valueAt(*entry), 4, value);
        return std::string(tag == kImageWidth ? "ImageWidth" : "ImageLength") + " " + std::to_string(old) +
               " -> LONG " + std::to_string(value);
    }
    const uint64_t value = interestingValue(random, old, entry->type == 3 ? 16 : 32);
    layout.setValue(file, *entry, 0, value);
    return std::string(tag == kImageWidth ? "ImageWidth" : "ImageLength") + " " + std::to_string(old) + " -> " +
           std::to_string(value);
}

std::string damagePixelFormat(std::string& file, const TiffLayout& layout, Random& random) {
    switch (random.below(9)) {
        case 0:
            return setTag(file, layout, kBitsPerSample, "BitsPerSample", {0, 1, 2, 4, 7, 8, 12, 16, 24, 32, 64, 255},
                          random);
        case 1:
            return setTag(file, layout, kSamplesPerPixel, "SamplesPerPixel", {0, 1, 2, 3, 4, 5, 8, 255, 65535}, random);
        case 2:
            return setTag(file, layout, kCompression, "Compression",
                          {0, 1, 2, 3, 4, 5, 6, 7, 8, 32773, 32946, 34676, 34712, 50000}, random);
        case 3:
            return setTag(file, layout, kPhotometric, "Photometric",
                          {0, 1, 2, 3, 4, 5, 6, 8, 9, 10, 32844, 32845, 34892, 99}, random);
        case 4: return setTag(file, layout, kPlanarConfig, "PlanarConfig", {0, 1, 2, 3}, random);
        case 5: return setTag(file, layout, kSampleFormat, "SampleFormat", {0, 1, 2, 3, 4, 5, 6}, random);
        case 6: return setTag(file, layout, kExtraSamples, "ExtraSamples", {0, 1, 2, 3}, random);
        case 7: return setTag(file, layout, kPredictor, "Predictor", {0, 1, 2, 3, 4}, random);
        default:
            return setTag(file, layout, random.percent(50) ? kFillOrder : kOrientation, "FillOrder/Orientation",
                          {0, 1, 2, 5, 8, 9, 255}, random);
    }
}

std::string damageStructure(std::string& file, const TiffLayout& layout, Random& random) {
    const uint64_t size = file.size();
    switch (random.below(9)) {
        case 0: return setTag(file, layout, kRowsPerStrip, "RowsPerStrip", {0, 1, 2, 3, 7, 0xFFFF, 0xFFFFFFFF}, random);
        case 1:
            return setTag(file, layout, random.percent(50) ? kStripOffsets : kTileOffsets, "Strip/TileOffsets",
                          {0, 1, 7, 8, size - 1, size, size + 100, 0xFFFFFFFF}, random);
        case 2:
            return setTag(file, layout, random.percent(50) ? kStripByteCounts : kTileByteCounts, "Strip/TileByteCounts",
                          {0, 1, 2, size, 0x7FFFFFFF, 0xFFFFFFFF}, random);
        case 3:
            return setTag(file, layout, random.percent(50) ? kTileWidth : kTileLength, "TileWidth/Length",
                          {0, 1, 8, 15, 16, 17, 32, 65535, 0xFFFFFFFF}, random);
        case 4: {
            // The strip or tile arrays of another length than the image needs.
            const uint16_t tags[] = {kStripOffsets,   kStripByteCounts, kTileOffsets,
                                     kTileByteCounts, kBitsPerSample,   kColorMap};
            const TiffEntry* entry = layout.find(tags[random.below(std::size(tags))]);
            if (!entry) entry = &random.pick(layout.entries);
            const uint64_t count =
                random.percent(50) ? entry->count + random.between(-2, 2) : interestingValue(random, entry->count, 32);
            layout.put(file, layout.countAt(*entry), layout.offsetSize(), count);
            return "tag " + std::to_string(entry->tag) + " count " + std::to_string(entry->count) + " -> " +
                   std::to_string(count);
        }
        case 5: {
            const uint16_t tags[] = {kColorMap, kJpegTables, kExifIfd, kIccProfile};
            const TiffEntry* entry = layout.find(tags[random.below(std::size(tags))]);
            if (!entry) return damageTiffStructure(file, random);
            return damageTiffEntry(file, layout, *entry, random);
        }
        default: return damageTiffStructure(file, random);
    }
}

// The strips or tiles: where the coded pixels are.
std::vector<std::pair<size_t, size_t>> dataRanges(const std::string& file, const TiffLayout& layout) {
    std::vector<std::pair<size_t, size_t>> ranges;
    for (auto [offsets_tag, counts_tag] :
         {std::pair{kStripOffsets, kStripByteCounts}, std::pair{kTileOffsets, kTileByteCounts}}) {
        const TiffEntry* offsets = layout.find(offsets_tag);
        const TiffEntry* counts = layout.find(counts_tag);
        if (!offsets || !counts) continue;
        const std::vector<uint32_t> at = layout.values(file, *offsets), size = layout.values(file, *counts);
        for (size_t i = 0; i < std::min(at.size(), size.size()); ++i)
            if (size[i] && at[i] < file.size() && size[i] <= file.size() - at[i]) ranges.push_back({at[i], size[i]});
    }
    return ranges;
}

std::string damageStream(std::string& file, const TiffLayout& layout, Random& random) {
    const std::vector<std::pair<size_t, size_t>> ranges = dataRanges(file, layout);
    if (ranges.empty()) return "no strips or tiles";
    const auto [begin, size] = random.pick(ranges);
    switch (random.below(3)) {
        case 0: {
            const size_t at = begin + random.below(size),
                         count = std::min<size_t>(begin + size - at, random.between(1, 16));
            file.replace(at, count, random.bytes(count));
            return std::to_string(count) + " random bytes in the strip/tile at " + std::to_string(begin);
        }
        case 1: {
            const size_t at = begin + random.below(size);
            file[at] = char(uint8_t(file[at]) ^ (1u << random.below(8)));
            return "bit flipped in the strip/tile at " + std::to_string(begin);
        }
        default: {
            // One strip's data in place of another's, which decodes to the wrong amount.
            const auto [other, other_size] = random.pick(ranges);
            const size_t count = std::min(size, other_size);
            file.replace(begin, count, file.substr(other, count));
            return "strip/tile at " + std::to_string(begin) + " overwritten with the one at " + std::to_string(other);
        }
    }
}

}  // namespace

std::string damageTiff(std::string& file, DamageKind kind, Random& random) {
    const std::optional<TiffLayout> layout = parseTiff(file);
    if (!layout || layout->entries.empty()) return "not a TIFF";
    switch (kind) {
        case DamageKind::Size: return damageSize(file, *layout, random);
        case DamageKind::PixelFormat: return damagePixelFormat(file, *layout, random);
        case DamageKind::Structure: return damageStructure(file, *layout, random);
        default: return damageStream(file, *layout, random);
    }
}

}  // namespace fuzz
