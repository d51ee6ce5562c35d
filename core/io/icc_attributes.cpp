// Follows the ICC.1 profile layout: a 128-byte header (big-endian), a tag count, then
// 12-byte tag entries (signature, offset, size). Names and wording are OpenImageIO 2.4's.
#include "icc_attributes.h"

#include <codecvt>
#include <cstdio>
#include <cstring>
#include <locale>
#include <string_view>

namespace ddt {

namespace {

const size_t kHeaderBytes = 128;

uint32_t bigEndian32(const uint8_t* at) { return uint32_t(at[0]) << 24 | uint32_t(at[1]) << 16 | uint32_t(at[2]) << 8 | at[3]; }
uint16_t bigEndian16(const uint8_t* at) { return uint16_t(at[0] << 8 | at[1]); }

std::string_view fourCharacters(const uint8_t* at) { return {reinterpret_cast<const char*>(at), 4}; }

// The names OpenImageIO gives the header's signatures; "" for one it does not know.
std::string deviceClassName(std::string_view code) {
    const std::pair<const char*, const char*> names[] = {
        {"scnr", "Input device profile"}, {"mntr", "Display device profile"}, {"prtr", "Output device profile"},
        {"link", "DeviceLink profile"},   {"spac", "ColorSpace profile"},     {"abst", "Abstract profile"},
        {"nmcl", "NamedColor profile"},
    };
    for (const auto& [known, name] : names)
        if (code == known) return name;
    return "";
}

std::string colourSpaceName(std::string_view code) {
    // OpenImageIO's table lists "BCLR" twice (11 and 12 colours); the first is the one it finds.
    const std::pair<const char*, const char*> names[] = {
        {"XYZ ", "XYZ"},      {"Lab ", "CIELAB"},   {"Luv ", "CIELUV"},   {"YCbr", "YCbCr"},    {"Yxy ", "CIEYxy"},
        {"RGB ", "RGB"},      {"GRAY", "Gray"},     {"HSV ", "HSV"},      {"HLS ", "HLS"},      {"CMYK", "CMYK"},
        {"CMY ", "CMY"},      {"2CLR", "2 color"},  {"3CLR", "3 color"},  {"4CLR", "4 color"},  {"5CLR", "5 color"},
        {"6CLR", "6 color"},  {"7CLR", "7 color"},  {"8CLR", "8 color"},  {"9CLR", "9 color"},  {"ACLR", "10 color"},
        {"BCLR", "11 color"}, {"CCLR", "13 color"}, {"DCLR", "14 color"}, {"ECLR", "15 color"}, {"FCLR", "16 color"},
    };
    for (const auto& [known, name] : names)
        if (code == known) return name;
    return "";
}

std::string platformName(std::string_view code) {
    const std::pair<const char*, const char*> names[] = {
        {"APPL", "Apple Computer, Inc."}, {"MSFT", "Microsoft Corporation"},
        {"SGI ", "Silicon Graphics, Inc."}, {"SUNW", "Sun Microsystems, Inc."},
    };
    for (const auto& [known, name] : names)
        if (code == known) return name;
    return "";
}

std::string renderingIntentName(uint32_t intent) {
    const char* names[] = {"Perceptual", "Media-relative colorimetric", "Saturation", "ICC-absolute colorimetric"};
    return intent < 4 ? names[intent] : "Unknown";
}

std::string tagName(std::string_view signature) {
    const std::pair<const char*, const char*> names[] = {
        {"targ", "characterization_target"}, {"cprt", "copyright"}, {"desc", "profile_description"},
        {"dmdd", "device_model_description"}, {"dmnd", "device_manufacturer_description"},
        {"vued", "viewing_conditions_description"},
    };
    for (const auto& [known, name] : names)
        if (signature == known) return std::string("ICCProfile:") + name;
    return "ICCProfile:" + std::string(signature);
}

// A string attribute ends at its first NUL in OpenImageIO, whatever the length it was given.
std::string upToNul(const char* text, size_t size) { return std::string(text, strnlen(text, size)); }

std::string hex(uint32_t value) {
    char text[16];
    std::snprintf(text, sizeof text, "%x", value);
    return text;
}

void setUInt32(ImageAttributes& attributes, std::string name, uint32_t value) {
    ImageAttribute attribute{std::move(name), {AttributeType::Base::UInt32, 1, AttributeType::Meaning::None, 0}, {}, {}};
    const auto* bytes = reinterpret_cast<const uint8_t*>(&value);
    attribute.bytes.assign(bytes, bytes + sizeof value);
    attributes.set(std::move(attribute));
}

void addHeaderAttributes(const uint8_t* header, ImageAttributes& attributes) {
    setUInt32(attributes, "ICCProfile:profile_size", bigEndian32(header));
    setUInt32(attributes, "ICCProfile:cmm_type", bigEndian32(header + 4));
    const uint8_t* version = header + 8;
    attributes.set("ICCProfile:profile_version", std::to_string(version[0]) + "." + std::to_string(version[1] >> 4) +
                                                     "." + std::to_string(version[1] & 0xF));
    attributes.set("ICCProfile:device_class", deviceClassName(fourCharacters(header + 12)));
    attributes.set("ICCProfile:color_space", colourSpaceName(fourCharacters(header + 16)));
    attributes.set("ICCProfile:profile_connection_space", colourSpaceName(fourCharacters(header + 20)));
    attributes.set("ICCProfile:platform_signature", platformName(fourCharacters(header + 40)));
    char date[64];
    const uint8_t* d = header + 24;  // year, month, day, hours, minutes, seconds
    std::snprintf(date, sizeof date, "%02d:%02d:%02d %02d:%02d:%02d", bigEndian16(d), bigEndian16(d + 2), bigEndian16(d + 4),
                  bigEndian16(d + 6), bigEndian16(d + 8), bigEndian16(d + 10));
    attributes.set("ICCProfile:creation_date", date);
    const uint32_t flags = bigEndian32(header + 44);
    attributes.set("ICCProfile:flags", std::string(flags & 1 ? "Embedded " : "Not Embedded") + ", " +
                                           (flags & 2 ? "Dependent" : "Independent"));
    attributes.set("ICCProfile:manufacturer", hex(bigEndian32(header + 48)));
    attributes.set("ICCProfile:model", hex(bigEndian32(header + 52)));
    const uint32_t device = bigEndian32(header + 60);  // the low half of the 64-bit device attributes
    attributes.set("ICCProfile:attributes", std::string(device & 1 ? "Transparency " : "Reflective") + ", " +
                                                (device & 2 ? "Matte" : "Glossy") + ", " +
                                                (device & 4 ? "Negative" : "Positive") + ", " +
                                                (device & 8 ? "Black & White" : "Color"));
    attributes.set("ICCProfile:rendering_intent", renderingIntentName(bigEndian32(header + 64)));
    attributes.set("ICCProfile:creator_signature", hex(bigEndian32(header + 80)));
}

// The English record of a multi-localized Unicode tag (UTF-16BE), as UTF-8; false where the
// records run past the profile or are not 12 bytes each (OpenImageIO stops the whole profile).
bool englishText(const std::vector<uint8_t>& profile, size_t tag_offset, std::string& text, bool& found) {
    size_t at = tag_offset + 8;  // past "mluc" and 4 reserved bytes
    if (at + 8 > profile.size()) return false;
    const uint32_t records = bigEndian32(&profile[at]), record_bytes = bigEndian32(&profile[at + 4]);
    at += 8;
    if (record_bytes != 12) return false;
    for (uint32_t r = 0; r < records; ++r) {
        if (at + 12 > profile.size()) return false;
        const uint16_t language = bigEndian16(&profile[at]);
        const uint32_t length = bigEndian32(&profile[at + 4]), offset = bigEndian32(&profile[at + 8]);
        at += 12;
        if (language != ('e' << 8 | 'n')) continue;
        const size_t start = tag_offset + offset;
        if (start + length > profile.size()) return false;  // OpenImageIO reads past the end here
        std::u16string utf16(length / 2, u'\0');
        for (size_t i = 0; i < utf16.size(); ++i) utf16[i] = char16_t(bigEndian16(&profile[start + 2 * i]));
        std::wstring_convert<std::codecvt_utf8_utf16<char16_t>, char16_t> convert;
        const std::string utf8 = convert.to_bytes(utf16);
        text = upToNul(utf8.data(), utf8.size());
        found = true;
        return true;
    }
    return true;
}

}  // namespace

void addIccAttributes(const std::vector<uint8_t>& profile, ImageAttributes& attributes) {
    const uint32_t acsp = 0x61637370;  // the header's magic number, "acsp"
    if (profile.size() < kHeaderBytes || bigEndian32(&profile[36]) != acsp || bigEndian32(&profile[0]) != profile.size())
        return;
    addHeaderAttributes(profile.data(), attributes);
    if (kHeaderBytes + 4 > profile.size()) return;
    const uint32_t tags = bigEndian32(&profile[kHeaderBytes]);
    size_t entry = kHeaderBytes + 4;
    for (uint32_t t = 0; t < tags; ++t, entry += 12) {
        if (entry + 12 > profile.size()) return;
        const std::string_view signature = fourCharacters(&profile[entry]);
        const uint64_t offset = bigEndian32(&profile[entry + 4]), size = bigEndian32(&profile[entry + 8]);
        if (offset + size > profile.size()) return;
        if (size < 4) continue;  // no type signature: OpenImageIO would read past the tag
        const std::string_view type = fourCharacters(&profile[offset]);
        const auto* bytes = reinterpret_cast<const char*>(profile.data());
        if (type == "text" && size >= 8) attributes.set(tagName(signature), upToNul(bytes + offset + 8, size - 8));
        else if (type == "desc" && size >= 12) attributes.set(tagName(signature), upToNul(bytes + offset + 12, size - 12));
        else if (type == "mluc") {
            std::string text;
            bool found = false;
            if (!englishText(profile, offset, text, found)) return;
            if (found) attributes.set(tagName(signature), text);
        }
    }
}

}  // namespace ddt
