// ddtup's EXIF blocks (core/io/exif.h) against OpenImageIO 2.4's own decode_exif and
// encode_exif, the reference they replace: the same attributes (names, types, values, order)
// from the same blocks — little- and big-endian, written by OpenImageIO, built here with every
// field type, taken from camera photographs, truncated, corrupted, with pointers out of range
// or in loops — and the same bytes from the same attributes.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>
#include <OpenImageIO/tiffutils.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "exif.h"
#include "exif_tags.h"
#include "oiio_metadata.h"

using ddt::AttributeType;
using ddt::ImageAttribute;
using ddt::ImageAttributes;
using Bytes = std::vector<uint8_t>;

namespace {

// --- The two implementations side by side -----------------------------------------------

struct Decoded {
    bool ok;
    ImageAttributes attributes;
};

Decoded oiioDecode(const Bytes& block, const ImageAttributes& before = {}) {
    OIIO::ImageSpec spec;
    ddt::addAttributes(before, spec);
    const bool ok = OIIO::decode_exif(OIIO::cspan<uint8_t>(block.data(), block.size()), spec);
    return {ok, ddt::attributesOf(spec)};
}

Decoded ddtupDecode(const Bytes& block, const ImageAttributes& before = {}) {
    Decoded decoded{false, before};
    decoded.ok = ddt::decodeExif(block.data(), block.size(), decoded.attributes);
    return decoded;
}

// OpenImageIO's block for the attributes (little-endian unless asked), when an attribute's name
// starts with "Exif:" or "GPS:".
std::string oiioEncode(const ImageAttributes& attributes, OIIO::endian order = OIIO::endian::little) {
    bool any = false;
    for (const ImageAttribute& attribute : attributes.all())
        any = any || OIIO::Strutil::istarts_with(attribute.name, "Exif:") || OIIO::Strutil::istarts_with(attribute.name, "GPS:");
    if (!any) return "";
    OIIO::ImageSpec spec;
    ddt::addAttributes(attributes, spec);
    std::vector<char> block;
    OIIO::encode_exif(spec, block, order);
    return std::string(block.begin(), block.end());
}

Bytes bytesOf(const std::string& text) { return Bytes(text.begin(), text.end()); }

// Every attribute, one a line: name, type, value bytes in hex, strings; for comparing (a
// difference shows as the line that differs).
std::string describe(const ImageAttributes& attributes) {
    std::string text;
    for (const ImageAttribute& a : attributes.all()) {
        text += a.name + " base " + std::to_string(int(a.type.base)) + " x" + std::to_string(a.type.aggregate) + " meaning " +
                std::to_string(int(a.type.meaning)) + " [" + std::to_string(a.type.array_length) + "] =";
        for (uint8_t byte : a.bytes) text += ' ' + std::to_string(byte);
        for (const std::string& s : a.strings) text += " \"" + std::string(s.data(), s.size()) + "\"(" + std::to_string(s.size()) + ")";
        text += '\n';
    }
    return text;
}

void requireSameDecoding(const Bytes& block, const ImageAttributes& before = {}) {
    const Decoded theirs = oiioDecode(block, before);
    const Decoded ours = ddtupDecode(block, before);
    CAPTURE(block.size());
    REQUIRE(describe(ours.attributes) == describe(theirs.attributes));
    REQUIRE(ours.ok == theirs.ok);
}

// --- Blocks built here, in either byte order ----------------------------------------------

// A directory entry: its value's bytes are given in little-endian order, units of `unit` bytes
// swapped for a big-endian block. `points_to` ≥ 0: the value is that directory's offset.
struct Field {
    uint16_t tag;
    uint16_t type;
    uint32_t count;
    Bytes value;
    size_t unit = 1;
    int points_to = -1;
};

Bytes le(uint64_t value, size_t bytes) {
    Bytes out;
    for (size_t i = 0; i < bytes; ++i) out.push_back(uint8_t(value >> (8 * i)));
    return out;
}

Field shorts(uint16_t tag, std::vector<uint16_t> values) {
    Field f{tag, 3, uint32_t(values.size()), {}, 2};
    for (uint16_t v : values) for (uint8_t b : le(v, 2)) f.value.push_back(b);
    return f;
}
Field longs(uint16_t tag, std::vector<uint32_t> values, uint16_t type = 4) {
    Field f{tag, type, uint32_t(values.size()), {}, 4};
    for (uint32_t v : values) for (uint8_t b : le(v, 4)) f.value.push_back(b);
    return f;
}
// Pairs of numerator, denominator; type 5 RATIONAL, 10 SRATIONAL.
Field rationals(uint16_t tag, std::vector<std::pair<int64_t, int64_t>> values, uint16_t type = 5) {
    Field f{tag, type, uint32_t(values.size()), {}, 4};
    for (auto [n, d] : values) {
        for (uint8_t b : le(uint64_t(n), 4)) f.value.push_back(b);
        for (uint8_t b : le(uint64_t(d), 4)) f.value.push_back(b);
    }
    return f;
}
// Bytes as they are, with the count given (ASCII 2, BYTE 1, UNDEFINED 7, SBYTE 6).
Field raw(uint16_t tag, uint16_t type, const std::string& bytes) {
    return Field{tag, type, uint32_t(bytes.size()), Bytes(bytes.begin(), bytes.end())};
}
Field pointer(uint16_t tag, int directory) { return Field{tag, 4, 1, Bytes(4, 0), 4, directory}; }

// A TIFF structure: the header, then each directory followed by its long values; directory 0
// is the first, `next` chains the first to the one after it (a thumbnail's).
Bytes buildBlock(const std::vector<std::vector<Field>>& directories, bool big_endian, int next = -1) {
    auto put = [&](Bytes& out, uint64_t v, size_t n) {
        Bytes b = le(v, n);
        if (big_endian) std::reverse(b.begin(), b.end());
        out.insert(out.end(), b.begin(), b.end());
    };
    auto ordered = [&](const Field& f) {
        Bytes v = f.value;
        if (big_endian)
            // Swapped byte by byte: std::reverse here made GCC 12 with -march=native warn of a
            // 32-byte write into the unit (-Wstringop-overflow), a false alarm.
            for (size_t i = 0; i + f.unit <= v.size(); i += f.unit)
                for (size_t lo = i, hi = i + f.unit - 1; lo < hi; ++lo, --hi) std::swap(v[lo], v[hi]);
        return v;
    };
    // Where each directory starts: after the header and the directories (and values) before it.
    std::vector<size_t> starts;
    size_t at = 8;
    for (const auto& fields : directories) {
        starts.push_back(at);
        at += 2 + 12 * fields.size() + 4;
        for (const Field& f : fields) at += f.value.size() > 4 ? f.value.size() : 0;
    }
    Bytes out = {uint8_t(big_endian ? 'M' : 'I'), uint8_t(big_endian ? 'M' : 'I')};
    put(out, 42, 2);
    put(out, starts[0], 4);
    for (size_t d = 0; d < directories.size(); ++d) {
        const auto& fields = directories[d];
        put(out, fields.size(), 2);
        size_t value_at = starts[d] + 2 + 12 * fields.size() + 4;
        Bytes values;
        for (const Field& f : fields) {
            put(out, f.tag, 2);
            put(out, f.type, 2);
            put(out, f.count, 4);
            if (f.points_to >= 0) {
                put(out, starts[size_t(f.points_to)], 4);
            } else if (f.value.size() > 4) {
                put(out, value_at + values.size(), 4);
                Bytes v = ordered(f);
                values.insert(values.end(), v.begin(), v.end());
            } else {
                Bytes v = ordered(f);
                v.resize(4, 0);
                out.insert(out.end(), v.begin(), v.end());
            }
        }
        put(out, d == 0 && next >= 0 ? starts[size_t(next)] : 0, 4);
        out.insert(out.end(), values.begin(), values.end());
    }
    return out;
}

// A camera's block with every field type on known and unknown tags, in the EXIF, GPS and
// interoperability directories, and a thumbnail's directory (which is not read).
std::vector<std::vector<Field>> cameraDirectories() {
    return {
        // 0: the first directory
        {raw(271, 2, std::string("NIKON CORPORATION\0", 18)), raw(272, 2, std::string("D7\0", 3)), shorts(274, {6}),
         rationals(282, {{300, 1}}), rationals(283, {{72, 1}}), shorts(296, {2}), raw(305, 2, std::string("ver\0\0\0 x\0", 9)),
         raw(306, 2, "2024:05:06 07:08:09"), shorts(256, {4000}), longs(257, {3000}), shorts(258, {8, 8, 8}),
         shorts(530, {2, 1}), shorts(531, {1}), raw(270, 2, std::string("\0\0\0", 3)), raw(315, 2, ""),
         raw(33432, 2, std::string("ab\0c\0\0", 6)), pointer(34665, 1), pointer(34853, 2), longs(0xC612, {7})},
        // 1: EXIF
        {rationals(33434, {{1, 250}}), rationals(33437, {{28, 10}}), shorts(34850, {2}), shorts(34855, {100, 200}),
         raw(36864, 7, "0231"), raw(36867, 2, std::string("2024:05:06 07:08:09\0", 20)), raw(37121, 7, std::string("\1\2\3\0", 4)),
         rationals(37377, {{-8, 1}}, 10), rationals(37378, {{0, 0}}), rationals(37379, {{-1, 3}}, 10), rationals(37380, {{1, 0}}, 10),
         shorts(37383, {5}), longs(37385, {16}), rationals(37386, {{50, 1}}), raw(37500, 7, "Nikon\0\2\0\0\0MM\0*"),
         raw(37510, 7, "ASCII\0\0\0comment"), raw(37520, 2, "42"), raw(40960, 7, "0100"), shorts(40961, {1}),
         longs(40962, {4000}), shorts(40963, {3000}), pointer(40965, 3), shorts(41492, {10, 20}), raw(41728, 7, "\3"),
         raw(41729, 1, "\1"), rationals(42034, {{18, 1}, {55, 1}, {35, 10}, {56, 10}}), raw(42036, 2, "18-55mm"),
         raw(41986, 6, "\1"), longs(41987, {1}, 9), longs(41988, {0x3F800000}, 11), shorts(41990, {}),
         Field{41989, 8, 1, le(uint16_t(-3), 2), 2}, Field{42240, 12, 1, le(0x3FF0000000000000, 8), 8},
         rationals(37382, {}), raw(37394, 2, std::string("A\0", 2)), rationals(41483, {{3, 2}, {5, 4}}),
         longs(34864, {}), Field{42016, 99, 1, Bytes(4, 1)}},
        // 2: GPS
        {raw(0, 1, std::string("\2\3\0\0", 4)), raw(1, 2, std::string("N\0", 2)), rationals(2, {{48, 1}, {51, 1}, {2999, 100}}),
         raw(3, 2, std::string("E\0", 2)), rationals(4, {{2, 1}, {17, 1}, {4001, 100}}), raw(5, 1, std::string("\1", 1)),
         rationals(6, {{35, 1}}), rationals(7, {{12, 1}, {30, 1}, {0, 1}}), raw(27, 7, "ASCII\0\0\0GPS"),
         raw(29, 2, "2024:05:06"), shorts(30, {1}), shorts(99, {1})},
        // 3: interoperability
        {raw(1, 2, std::string("R98\0", 4)), raw(2, 7, "0100"), shorts(274, {3})},
        // 4: the thumbnail's
        {shorts(259, {6}), shorts(274, {8}), raw(315, 2, "thumbnail")},
    };
}

Bytes cameraBlock(bool big_endian) { return buildBlock(cameraDirectories(), big_endian, 4); }

// A Canon camera's block: its maker note (directory 5) with every tag OpenImageIO reads, and
// some it does not. `make_last`: the make comes after the EXIF directory, so that the maker
// note is read at the end.
Bytes canonBlock(const std::string& make, bool make_last, bool big_endian) {
    auto directories = cameraDirectories();
    auto& first = directories[0];
    first.erase(first.begin());  // Nikon's make
    const Field make_field = raw(271, 2, make + std::string(1, '\0'));
    if (make_last) first.push_back(make_field);
    else first.insert(first.begin(), make_field);
    auto& exif = directories[1];
    for (Field& f : exif)
        if (f.tag == 37500) f = Field{37500, 7, 600, Bytes(4, 0), 4, 5};
    std::vector<uint16_t> settings(47), focal = {1, 50, 2240, 1490}, shot(34), panorama(6), sensor(17);
    for (size_t i = 0; i < settings.size(); ++i) settings[i] = i % 5 == 0 ? 0xFFFF : uint16_t(i * 3);  // -1: no value
    for (size_t i = 0; i < shot.size(); ++i) shot[i] = uint16_t(int16_t(i * 7 - 100));
    for (size_t i = 0; i < sensor.size(); ++i) sensor[i] = uint16_t(6000 + i);
    Field shot_info = shorts(4, shot);
    shot_info.type = 8;  // SSHORT
    directories.push_back({shorts(1, settings), shorts(2, focal), shorts(3, {1, 2, 3, 4}), shot_info, shorts(5, panorama),
                           raw(6, 2, "IMG:EOS 5D JPEG"), raw(7, 2, std::string("Firmware 1.0.2\0", 15)), longs(8, {1001234}),
                           raw(9, 2, "Owner"), longs(12, {123456789}), longs(16, {0x80000213}), longs(19, {0, 5471, 0, 3647}),
                           longs(21, {1}), shorts(26, {0}), shorts(28, {0}), longs(30, {0x01020300}), longs(35, {8, 0}),
                           raw(40, 1, std::string(16, '\7')), raw(149, 2, "EF24-105mm f/4L IS USM"), shorts(152, {0, 0, 0, 0}),
                           shorts(174, {5200}), shorts(224, sensor), raw(0x4010, 2, "")});
    return buildBlock(directories, big_endian, 4);
}

std::vector<Bytes> canonBlocks() {
    std::vector<Bytes> blocks;
    for (bool big_endian : {false, true})
        for (const auto& [make, last] : {std::pair{"Canon", false}, std::pair{"Canon", true}, std::pair{"CANON", false}})
            blocks.push_back(canonBlock(make, last, big_endian));
    return blocks;
}

// The EXIF blocks of JPEG files: APP1 segments that start with "Exif\0\0".
std::vector<Bytes> jpegExifBlocks(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<Bytes> blocks;
    for (size_t at = 2; at + 4 <= file.size() && uint8_t(file[at]) == 0xFF;) {
        const uint8_t marker = uint8_t(file[at + 1]);
        const size_t length = size_t(uint8_t(file[at + 2])) << 8 | uint8_t(file[at + 3]);
        if (marker == 0xDA || at + 2 + length > file.size()) break;  // the scan: no more headers
        const std::string segment = file.substr(at + 4, length - 2);
        if (marker == 0xE1 && segment.compare(0, 6, std::string("Exif\0\0", 6)) == 0) blocks.push_back(bytesOf(segment));
        at += 2 + length;
    }
    return blocks;
}

// Camera photographs on this machine, if any (not in the repository: their licences are not
// known), and the test images.
std::vector<Bytes> photographBlocks() {
    std::vector<Bytes> blocks;
    for (const char* folder : {"/tmp/photos", DDTUP_TEST_DATA}) {
        std::error_code error;
        for (const auto& entry : std::filesystem::recursive_directory_iterator(folder, error)) {
            const std::string extension = entry.path().extension().string();
            if (extension == ".jpg" || extension == ".jpeg" || extension == ".JPG")
                for (Bytes& block : jpegExifBlocks(entry.path())) blocks.push_back(std::move(block));
        }
    }
    return blocks;
}

// --- Attribute sets ---------------------------------------------------------------------

ImageAttribute numbers(const std::string& name, AttributeType::Base base, const void* values, size_t count, size_t bytes) {
    ImageAttribute a{name, {}, {}, {}};
    a.type.base = base;
    a.type.array_length = count > 1 ? uint32_t(count) : 0;
    a.bytes.assign(static_cast<const uint8_t*>(values), static_cast<const uint8_t*>(values) + count * bytes);
    return a;
}
ImageAttribute floats(const std::string& name, std::vector<float> values) {
    return numbers(name, AttributeType::Base::Float, values.data(), values.size(), 4);
}

// A value for each tag of OpenImageIO's own tables, of the type its table says (floats for
// rationals, of the table's count; a string for ASCII; an int otherwise), in table order.
ImageAttributes everyTag(int seed) {
    std::mt19937 random{uint32_t(seed)};
    ImageAttributes attributes;
    for (const char* table : {"Exif", "GPS"}) {
        for (const OIIO::TagInfo& tag : OIIO::tag_table(table)) {
            const std::string name = tag.name;
            if (tag.tifftype == TIFF_ASCII) {
                const size_t length = random() % 12;  // some fit in an entry's 4 bytes
                std::string text;
                for (size_t i = 0; i < length; ++i) text += char('a' + random() % 26);
                attributes.append({name, {AttributeType::Base::String, 1, {}, 0}, {}, {text}});
            } else if (tag.tifftype == TIFF_RATIONAL || tag.tifftype == TIFF_SRATIONAL) {
                std::vector<float> values(size_t(std::max(tag.tiffcount, 1)));
                for (float& v : values) v = std::uniform_real_distribution<float>(-100.0f, 1000.0f)(random);
                attributes.append(floats(name, values));
            } else {
                attributes.set(name, int32_t(random() % 70000));
            }
        }
    }
    return attributes;
}

// Rationals that OpenImageIO's conversion treats in its own ways: exact inverses (0.5 → 1/0),
// decimals, negatives to an unsigned rational, out of range, NaN, infinity.
std::vector<float> awkwardFloats() {
    return {0.5f,  0.25f, 1.0f,   2.0f,  1 / 3.0f, 0.004f, 52.83f, 1e-7f,  -0.5f, -2.75f, 0.0f, -0.0f,
            3e9f,  1e20f, 1e-30f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
            -std::numeric_limits<float>::infinity(), 2147483520.0f, 123456.789f, 0.1f, 7.0f / 9.0f};
}

}  // namespace

TEST_CASE("exif: ddtup's tag tables are OpenImageIO's", "[io]") {
    // Same numbers, names, types and counts in the same order; a rule of its own where
    // OpenImageIO has a handler.
    for (const auto& [table, ours] : {std::pair{"Exif", ddt::exif::mainTags()}, std::pair{"GPS", ddt::exif::gpsTags()}}) {
        const OIIO::cspan<OIIO::TagInfo> theirs = OIIO::tag_table(table);
        REQUIRE(size_t(theirs.size()) == ours.size());
        for (size_t i = 0; i < ours.size(); ++i) {
            CAPTURE(table, i, theirs[i].name);
            CHECK(ours[i].number == theirs[i].tifftag);
            CHECK(std::string(ours[i].name) == theirs[i].name);
            CHECK(int(ours[i].type) == int(theirs[i].tifftype));
            CHECK(ours[i].count == theirs[i].tiffcount);
            CHECK((ours[i].reading != ddt::exif::Reading::ByType) == (theirs[i].handler != nullptr));
        }
    }
}

TEST_CASE("exif: a camera's block decodes as OpenImageIO decodes it, in either byte order", "[io]") {
    for (bool big_endian : {false, true}) {
        CAPTURE(big_endian);
        const Bytes block = cameraBlock(big_endian);
        requireSameDecoding(block);
        // The JPEG prefix is skipped.
        Bytes prefixed = bytesOf(std::string("Exif\0\0", 6));
        prefixed.insert(prefixed.end(), block.begin(), block.end());
        requireSameDecoding(prefixed);
        // Something to decode at all: the test would pass on two empty lists.
        CHECK(ddtupDecode(block).attributes.all().size() > 40);
    }
}

TEST_CASE("exif: Canon's maker note decodes as OpenImageIO decodes it", "[io]") {
    // At once where the make is known as "Canon"; at the end where it comes later, or as
    // "CANON" (OpenImageIO's two tests of the make differ in case).
    for (const Bytes& block : canonBlocks()) {
        requireSameDecoding(block);
        const ImageAttributes decoded = ddtupDecode(block).attributes;
        CHECK(decoded.find("Canon:MacroMode"));  // something of the maker note at all
    }
}

TEST_CASE("exif: attributes already there are kept, as OpenImageIO keeps them", "[io]") {
    const Bytes block = cameraBlock(false);
    ImageAttributes before;
    before.set("Orientation", int32_t(1));            // the same name: the block's is passed over
    before.set("xresolution", 12.0f);                  // another case: replaced where it stands
    before.set("Exif:ColorSpace", int32_t(0xFFFF));    // uncalibrated: no sRGB from it
    before.set("oiio:MakerNoteOffset", int32_t(-5));   // left, as OpenImageIO leaves one ≤ 0
    requireSameDecoding(block, before);
    ImageAttributes other;
    other.set("Make", std::string("Nikon"));        // the block's make is passed over
    other.set("ColorSpace", std::string("linear")); // not a number: sRGB
    requireSameDecoding(block, other);
}

TEST_CASE("exif: photographs' blocks decode as OpenImageIO decodes them", "[io]") {
    const std::vector<Bytes> blocks = photographBlocks();
    if (blocks.empty()) WARN("no photograph with EXIF here (/tmp/photos): only built blocks are compared");
    for (const Bytes& block : blocks) requireSameDecoding(block);
}

TEST_CASE("exif: OpenImageIO's blocks of every tag decode as OpenImageIO decodes them", "[io]") {
    for (int seed = 0; seed < 8; ++seed) {
        const ImageAttributes attributes = everyTag(seed);
        // Big-endian blocks from OpenImageIO's own writer too (its header's version is wrong,
        // which neither reader checks).
        for (OIIO::endian order : {OIIO::endian::little, OIIO::endian::big}) {
            const Bytes block = bytesOf(oiioEncode(attributes, order));
            requireSameDecoding(block);
            CHECK(ddtupDecode(block).attributes.all().size() > 60);
        }
    }
}

TEST_CASE("exif: damaged blocks decode as OpenImageIO decodes them, reading nothing outside", "[io]") {
    // Every block is copied to a buffer of its own size: AddressSanitizer (scripts/build
    // --sanitize) sees a read past its end.
    std::vector<Bytes> blocks = {cameraBlock(false), cameraBlock(true), bytesOf(oiioEncode(everyTag(1)))};
    for (Bytes& block : photographBlocks()) blocks.push_back(std::move(block));
    for (Bytes& block : canonBlocks()) blocks.push_back(std::move(block));

    SECTION("truncated at every length") {
        for (const Bytes& block : blocks)
            for (size_t size = 0; size < block.size(); ++size) {
                const Bytes truncated(block.begin(), block.begin() + ptrdiff_t(size));
                // Under 8 bytes OpenImageIO reads a whole header beyond the block: no reference.
                if (size < 8) {
                    CHECK_FALSE(ddtupDecode(truncated).ok);
                    CHECK(ddtupDecode(truncated).attributes.empty());
                } else {
                    requireSameDecoding(truncated);
                }
            }
    }
    SECTION("bytes changed at random") {
        std::mt19937 random{33};
        for (const Bytes& block : blocks)
            for (int trial = 0; trial < 3000; ++trial) {
                Bytes damaged = block;
                const int changes = 1 + int(random() % 4);
                for (int c = 0; c < changes; ++c) {
                    // Mostly in the header and directories, where offsets and counts are.
                    const size_t at = random() % 2 ? random() % std::min<size_t>(damaged.size(), 300) : random() % damaged.size();
                    damaged[at] = random() % 3 ? uint8_t(random()) : uint8_t(damaged[at] ^ (1u << (random() % 8)));
                }
                requireSameDecoding(damaged);
            }
    }
    SECTION("pointers out of range, and in loops") {
        for (bool big_endian : {false, true}) {
            CAPTURE(big_endian);
            auto directories = cameraDirectories();
            // EXIF points to itself and to GPS, GPS back to EXIF, interoperability to the first.
            directories[1].push_back(pointer(34665, 1));
            directories[1].push_back(pointer(34853, 2));
            directories[2].push_back(pointer(34665, 1));
            directories[3].push_back(pointer(40965, 0));
            requireSameDecoding(buildBlock(directories, big_endian));
            // Pointers and values past the end, at the end, and negative as an int.
            for (uint32_t offset : {0u, 7u, 1000000u, 0x80000000u, 0xFFFFFFFFu}) {
                CAPTURE(offset);
                auto bad = cameraDirectories();
                Bytes value = le(offset, 4);
                bad[0].push_back(Field{34665, 4, 1, value, 4});
                bad[0].push_back(Field{34853, 4, 1, value, 4});
                bad[1].push_back(Field{40965, 4, 1, value, 4});
                bad[1].push_back(Field{41486, 5, 1, value, 4});  // a RATIONAL's offset
                requireSameDecoding(buildBlock(bad, big_endian));
            }
            // Pointers and a value at the block's end, or one or two bytes before it.
            auto atEnd = [&](size_t end) {
                auto directories = cameraDirectories();
                directories[0].insert(directories[0].begin(), Field{34665, 4, 1, le(end, 4), 4});
                directories[0].insert(directories[0].begin(), Field{34853, 4, 1, le(end, 4), 4});
                directories[1].push_back(Field{41487, 5, 1, le(end - 8, 4), 4});
                return buildBlock(directories, big_endian);
            };
            const size_t size = atEnd(0).size();
            for (size_t end : {size, size - 1, size - 2}) requireSameDecoding(atEnd(end));
            // A GPS directory whose count reads as more than GPS's 32 tags.
            auto many = cameraDirectories();
            many[2].resize(33, shorts(30, {1}));
            requireSameDecoding(buildBlock(many, big_endian));
        }
        // A first directory that does not fit, and an unknown byte order.
        Bytes block = cameraBlock(false);
        block[8] = 0xFF;
        requireSameDecoding(block);
        block = cameraBlock(false);
        block[0] = 'X';
        requireSameDecoding(block);
    }
}

TEST_CASE("exif: blocks written are OpenImageIO's bytes for the same attributes", "[io]") {
    auto requireSameBlock = [](const ImageAttributes& attributes) {
        const std::string theirs = oiioEncode(attributes);
        CAPTURE(describe(attributes));
        REQUIRE(ddt::encodeExif(attributes) == theirs);
    };
    SECTION("every tag, in table order and shuffled") {
        for (int seed = 0; seed < 8; ++seed) {
            ImageAttributes attributes = everyTag(seed);
            requireSameBlock(attributes);
            std::vector<ImageAttribute> list = attributes.all();
            std::shuffle(list.begin(), list.end(), std::mt19937(uint32_t(seed)));
            ImageAttributes shuffled;
            for (ImageAttribute& a : list) shuffled.append(std::move(a));
            requireSameBlock(shuffled);
        }
    }
    SECTION("the attributes decoded from blocks, Canon's maker note's among them") {
        std::vector<Bytes> blocks = {cameraBlock(false), cameraBlock(true)};
        for (Bytes& block : photographBlocks()) blocks.push_back(std::move(block));
        for (Bytes& block : canonBlocks()) blocks.push_back(std::move(block));
        for (const Bytes& block : blocks) requireSameBlock(oiioDecode(block).attributes);
    }
    SECTION("Canon's maker note: attributes of other types, some arrays partly there") {
        ImageAttributes attributes = oiioDecode(canonBlock("Canon", false, false)).attributes;
        attributes.erase("Canon:FocalType");                         // the array's other values stay
        attributes.set("Canon:MacroMode", 70000);                   // wraps to 16 bits
        attributes.set("Canon:BaseISO", 12.7f);                     // a float: its int
        attributes.set("Canon:FileNumber", 3.5f);                   // a float's bytes, as they are
        attributes.set("Canon:OwnerName", std::string("a"));        // fits in the entry
        attributes.set("Canon:ModelID", int32_t(-1));
        requireSameBlock(attributes);
        // An "Exif:MakerNote" beside them stops OpenImageIO on an assertion (its EXIF directory
        // counted one entry too many); ddtup's note's entry replaces the attribute's, and the
        // directories are where the pointers say.
        attributes.set("Exif:MakerNote", int32_t(3));
        ImageAttributes decoded;
        REQUIRE(ddt::decodeExif(bytesOf(ddt::encodeExif(attributes)).data(), ddt::encodeExif(attributes).size(), decoded));
        CHECK(decoded.getInt("Canon:MacroMode") == 70000 - 65536);
        CHECK(decoded.getFloat("GPS:Altitude") == 35.0f);
        CHECK(decoded.getInt("Exif:Flash") == 16);
        ImageAttributes only_canon;
        only_canon.set("Make", std::string("canon"));
        only_canon.set("Canon:PanoramaDirection", int32_t(4));     // the maker note alone: EXIF's versions too
        only_canon.set("GPS:Altitude", 3.0f);
        requireSameBlock(only_canon);
    }
    SECTION("awkward rationals") {
        for (float f : awkwardFloats()) {
            CAPTURE(f);
            ImageAttributes attributes;
            attributes.append(floats("ExposureTime", {f}));                // RATIONAL, in the EXIF directory
            attributes.append(floats("Exif:ExposureBiasValue", {f}));      // SRATIONAL
            attributes.append(floats("XResolution", {f}));                 // RATIONAL, in the first
            attributes.append(floats("GPS:Latitude", {f, -f, f * 3}));     // three of them
            attributes.append(floats("Exif:LensSpecification", {f, 1, 2, f}));
            requireSameBlock(attributes);
        }
    }
    SECTION("types that do not fit a tag, names in other cases, repeated tags") {
        ImageAttributes attributes;
        const int16_t small[3] = {-2, 5, 9};
        const uint8_t octets[3] = {1, 2, 3};
        const double wide = 2.5;
        attributes.append(numbers("Orientation", AttributeType::Base::Int16, small, 3, 2));  // first of an array
        attributes.append(numbers("Exif:Flash", AttributeType::Base::UInt8, octets, 3, 1));  // not converted: left out
        attributes.append(numbers("Exif:FNumber", AttributeType::Base::Double, &wide, 1, 8)); // a double: left out
        attributes.set("Exif:PixelXDimension", 3.5f);                                        // a float for a LONG: left out
        attributes.set("Exif:FocalLength", int32_t(50));                                      // an int for a RATIONAL: left out
        attributes.set("ResolutionUnit", std::string("inch"));                               // a string for a SHORT
        attributes.set("Exif:UserComment", int32_t(300));                                    // BYTE: one, wrapped
        attributes.set("GPS:VersionID", int32_t(7));                                         // replaced by 2.2.0.0
        attributes.set("GPS:AltitudeRef", int32_t(1));
        attributes.set("gps:Altitude", 4.0f);                                                // "GPS:" is case-sensitive
        attributes.append({"make", {AttributeType::Base::String, 1, {}, 0}, {}, {"ab"}});    // fits in the entry
        attributes.append({"MAKE", {AttributeType::Base::String, 1, {}, 0}, {}, {"Canon EOS"}});  // replaces it
        attributes.append({"Model", {AttributeType::Base::String, 1, {}, 2}, {}, {"a", "b"}});    // an array: left out
        attributes.append({"Software", {AttributeType::Base::String, 1, {}, 0}, {}, {""}});       // empty: left out
        attributes.append({"Artist", {AttributeType::Base::String, 1, {}, 0}, {}, {std::string("a\0b", 3)}});
        attributes.set("Exif:ExifVersion", std::string("0220"));                              // UNDEFINED: not from attributes
        attributes.set("Exif:Gamma", 2.2f);                                                   // written with no value
        attributes.set("Exif:ISOSpeedRatings", int32_t(400));
        attributes.set("Exif:PhotographicSensitivity", int32_t(800));                        // the same tag
        attributes.set("Exif:LensMake", std::string("Lens Co"));                              // in the first directory
        attributes.set("Exif:ImageWidth", int32_t(10));                                       // passed over
        attributes.set("oiio:ColorSpace", std::string("sRGB"));                               // no EXIF tag
        requireSameBlock(attributes);
    }
    SECTION("only some directories, or none") {
        ImageAttributes gps_only;
        gps_only.append(floats("GPS:Altitude", {12.5f}));
        requireSameBlock(gps_only);
        ImageAttributes first_only;
        first_only.set("Exif:YCbCrPositioning", int32_t(1));
        first_only.set("Make", std::string("Camera"));
        requireSameBlock(first_only);
        ImageAttributes unknown;
        unknown.set("Exif:NoSuchTag", int32_t(1));
        requireSameBlock(unknown);
        ImageAttributes none;
        none.set("Orientation", int32_t(6));
        none.set("Make", std::string("Camera"));
        CHECK(ddt::encodeExif(none).empty());
        requireSameBlock(none);
    }
}
