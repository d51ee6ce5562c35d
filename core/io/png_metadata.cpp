#include "png_metadata.h"

#include <zlib.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>

namespace ddt {

namespace {

bool startsWithName(std::string_view text, std::string_view prefix) {
    return text.size() >= prefix.size() && sameName(text.substr(0, prefix.size()), prefix);
}

// The number after the word that starts `name` ("Gamma2.2": 2.2), as OpenImageIO 2.4's
// Strutil::parse_word and from_string<float> read it: 0 where there is none.
float numberAfterWord(const std::string& name) {
    size_t at = 0;
    while (at < name.size() && std::isspace(uint8_t(name[at]))) ++at;
    while (at < name.size() && std::isalpha(uint8_t(name[at]))) ++at;
    return std::strtof(name.c_str() + at, nullptr);
}

std::string bigEndian32(uint32_t value) {
    return {char(value >> 24), char(value >> 16), char(value >> 8), char(value)};
}

uint32_t readBigEndian32(const uint8_t* at) {
    return uint32_t(at[0]) << 24 | uint32_t(at[1]) << 16 | uint32_t(at[2]) << 8 | at[3];
}

// PNG stores gamma as 100000 times the file gamma (1 / the display gamma), rounded the way
// libpng does; libpng refuses values outside [16, 625000000].
std::optional<uint32_t> pngGamma(double file_gamma) {
    const double fixed = std::floor(100000.0 * file_gamma + 0.5);
    if (!(fixed >= 16 && fixed <= 625000000)) return std::nullopt;
    return uint32_t(fixed);
}

// sRGB's chromaticities (white, red, green, blue; x then y), as libpng writes them for sRGB.
std::string srgbChromaticities() {
    std::string data;
    for (uint32_t value : {31270u, 32900u, 64000u, 33000u, 30000u, 60000u, 15000u, 6000u}) data += bigEndian32(value);
    return data;
}

// What the colour space attribute says, as OpenImageIO 2.4 reads it: "sRGB", "Linear" (gamma
// 1), or "GammaG" (G in [0.01, 10], else oiio:Gamma).
struct ColourSpace {
    std::optional<uint32_t> gamma;  // the gAMA chunk's value
    bool srgb = false;
};

ColourSpace colourSpace(const ImageAttributes& attributes, std::vector<std::string>& left_out) {
    ColourSpace result;
    const std::string name = attributes.getString("oiio:ColorSpace");
    float display_gamma = 0;
    if (sameName(name, "Linear")) {
        display_gamma = 1.0f;
    } else if (startsWithName(name, "Gamma")) {
        display_gamma = attributes.getFloat("oiio:Gamma", 1.0f);
        const float stated = numberAfterWord(name);
        if (stated >= 0.01f && stated <= 10.0f) display_gamma = stated;
    } else if (sameName(name, "sRGB")) {
        result.srgb = true;
        result.gamma = 45455;  // sRGB's 1 / 2.2
        return result;
    } else {
        return result;
    }
    result.gamma = pngGamma(double(1.0f / display_gamma));
    if (!result.gamma) left_out.push_back("the gamma (" + std::string(name) + ")");
    return result;
}

// "" if `profile` is an ICC profile PNG may carry for an image of `channels`, else why not:
// whole (its header's size is its size, with the signature "acsp") and for the image's colour
// model (PNG specification, 11.3.3.3).
std::string iccProblem(const uint8_t* profile, size_t size, int channels) {
    if (size < 132 || readBigEndian32(profile) != size || std::memcmp(profile + 36, "acsp", 4) != 0) return "damaged";
    const bool grey = channels <= 2;
    if (std::memcmp(profile + 16, grey ? "GRAY" : "RGB ", 4) != 0)
        return "for the colour space \"" + std::string(reinterpret_cast<const char*>(profile) + 16, 4) + "\", the image is " +
               (grey ? "grey" : "RGB");
    return "";
}

std::optional<PngChunk> iccChunk(const ImageAttributes& attributes, uint32_t channels, std::vector<std::string>& left_out) {
    const ImageAttribute* icc = attributes.find("ICCProfile");
    if (!icc || icc->bytes.empty()) return std::nullopt;
    const uint8_t* profile = icc->bytes.data();
    const size_t size = icc->bytes.size();
    if (std::string problem = iccProblem(profile, size, int(channels)); !problem.empty()) {
        left_out.push_back("the ICC profile (" + problem + ")");
        return std::nullopt;
    }
    std::string compressed(compressBound(uLong(size)), '\0');
    uLongf compressed_size = compressed.size();
    if (compress2(reinterpret_cast<Bytef*>(compressed.data()), &compressed_size, profile, uLong(size), Z_DEFAULT_COMPRESSION) != Z_OK)
        throw std::bad_alloc();
    compressed.resize(compressed_size);
    // Its name, as OpenImageIO names it; compression method 0 (zlib).
    return PngChunk{"iCCP", std::string("Embedded Profile\0\0", 18) + compressed};
}

// The oFFs chunk: the image's offset in pixels, which OpenImageIO always writes.
PngChunk offsetChunk(int32_t x, int32_t y) {
    return {"oFFs", bigEndian32(uint32_t(x)) + bigEndian32(uint32_t(y)) + std::string(1, '\0')};
}

// The pHYs chunk from XResolution, YResolution, ResolutionUnit and PixelAspectRatio, as
// OpenImageIO 2.4 computes it (in single precision, truncated): pixels per metre for inches,
// centimetres and metres, else unit 0 (only the aspect ratio means something). A missing
// resolution follows the other and the aspect ratio, or is 100.
std::optional<PngChunk> resolutionChunk(const ImageAttributes& attributes, std::vector<std::string>& left_out) {
    const std::string unit = attributes.getString("ResolutionUnit");
    float x = attributes.getFloat("XResolution"), y = attributes.getFloat("YResolution");
    const float aspect = attributes.getFloat("PixelAspectRatio");
    if (!x && !y && !aspect && unit.empty()) return std::nullopt;
    bool metric = false;
    float scale = 1;
    if (sameName(unit, "meter") || sameName(unit, "m")) {
        metric = true;
    } else if (sameName(unit, "cm")) {
        metric = true;
        scale = 100;
    } else if (sameName(unit, "inch") || sameName(unit, "in")) {
        metric = true;
        scale = float(100.0 / 2.54);
    }
    if (aspect) {  // the aspect ratio decides the other
        if (x) y = 0.0f;
        else x = 0.0f;
    }
    const float ratio = aspect ? aspect : 1.0f;
    if (x == 0.0f && y == 0.0f) {
        x = 100.0f;
        y = x * ratio;
    } else if (x == 0.0f) {
        x = y / ratio;
    } else if (y == 0.0f) {
        y = x * ratio;
    }
    const float x_stored = x * scale, y_stored = y * scale;
    // PNG's four-byte numbers hold up to 2^31 - 1.
    if (!(x_stored >= 0.0f && x_stored < 2147483648.0f && y_stored >= 0.0f && y_stored < 2147483648.0f)) {
        left_out.push_back("the resolution (" + std::to_string(x) + " × " + std::to_string(y) + ")");
        return std::nullopt;
    }
    return PngChunk{"pHYs", bigEndian32(uint32_t(x_stored)) + bigEndian32(uint32_t(y_stored)) + std::string(1, char(metric ? 1 : 0))};
}

// Reads "YYYY:MM:DD HH:MM:SS" (or with - or / in the date) as OpenImageIO 2.4's
// Strutil::scan_datetime does: numbers after optional white space, separators right after them.
struct DateTimeReader {
    const char* at;
    bool number(int& value) {
        while (std::isspace(uint8_t(*at))) ++at;
        char* end = nullptr;
        const long parsed = std::strtol(at, &end, 10);
        if (end == at) return false;
        at = end;
        value = int(parsed);
        return true;
    }
    bool separator(std::string_view any_of) {
        if (!*at || any_of.find(*at) == std::string_view::npos) return false;
        ++at;
        return true;
    }
};

// The tIME chunk from a DateTime that reads as "YYYY:MM:DD HH:MM:SS" (or with - or / in the
// date); OpenImageIO drops any other.
std::optional<PngChunk> timeChunk(const std::string& date_time) {
    int year, month, day, hour, minute, second;
    DateTimeReader in{date_time.c_str()};
    const bool read = in.number(year) && in.separator(":-/") && in.number(month) && in.separator(":-/") && in.number(day) &&
                      in.number(hour) && in.separator(":") && in.number(minute) && in.separator(":") && in.number(second);
    if (!read || month < 1 || month > 12 || day < 1 || day > 31 || hour < 0 || hour > 23 || minute < 0 || minute > 59 ||
        second < 0 || second > 59 || year < 0 || year > 65535)
        return std::nullopt;
    const char data[7] = {char(year >> 8), char(year), char(month), char(day), char(hour), char(minute), char(second)};
    return PngChunk{"tIME", std::string(data, 7)};
}

// A text keyword as libpng makes one of a name: Latin-1 printable characters, each run of
// spaces or other characters one space, none at either end, at most 79 bytes. Empty if
// nothing is left (libpng then refuses the whole file).
std::string pngKeyword(const std::string& name) {
    std::string key;
    bool after_space = true;  // so that leading spaces are dropped
    for (size_t i = 0; i < name.size() && key.size() < 79; ++i) {
        const auto c = uint8_t(name[i]);
        if ((c > 32 && c <= 126) || c >= 161) {
            key += char(c);
            after_space = false;
        } else if (!after_space) {
            key += ' ';
            after_space = true;
        }
    }
    if (!key.empty() && key.back() == ' ') key.pop_back();
    return key;
}

// The names OpenImageIO 2.4 gives PNG's registered keywords.
std::string textKey(const std::string& name) {
    if (sameName(name, "Artist")) return "Author";
    if (sameName(name, "name") || sameName(name, "DocumentName")) return "Title";
    if (sameName(name, "description") || sameName(name, "ImageDescription")) return "Description";
    return name;
}

// Attributes stored otherwise (pHYs), or not at all.
bool storedApart(const std::string& name) {
    for (const char* apart : {"planarconfig", "compression", "ResolutionUnit", "XResolution", "YResolution"})
        if (sameName(name, apart)) return true;
    return false;
}

}  // namespace

PngMetadata pngMetadata(const PngMetadataSource& source) {
    const ImageAttributes& attributes = source.attributes;
    PngMetadata metadata;
    std::vector<PngChunk>& chunks = metadata.chunks;
    const ColourSpace colour = colourSpace(attributes, metadata.left_out);
    const std::optional<PngChunk> icc = iccChunk(attributes, source.channels, metadata.left_out);
    // libpng's order; with an ICC profile the sRGB chunk gives way to it.
    if (colour.gamma) chunks.push_back({"gAMA", bigEndian32(*colour.gamma)});
    if (icc) chunks.push_back(*icc);
    else if (colour.srgb) chunks.push_back({"sRGB", std::string(1, '\3')});  // rendering intent: absolute colorimetric
    if (colour.srgb) chunks.push_back({"cHRM", srgbChromaticities()});
    if (!source.exif.empty()) chunks.push_back({"eXIf", source.exif});
    chunks.push_back(offsetChunk(source.x_offset, source.y_offset));
    if (std::optional<PngChunk> resolution = resolutionChunk(attributes, metadata.left_out)) chunks.push_back(*resolution);

    std::optional<PngChunk> time;
    std::vector<PngChunk> texts;
    const AttributeType one_string{AttributeType::Base::String};
    for (const ImageAttribute& attribute : attributes.all()) {
        const std::string& name = attribute.name;
        if (storedApart(name) || attribute.type != one_string) continue;
        const std::string& text = attribute.strings.front();
        if (sameName(name, "DateTime")) {
            time = timeChunk(text);
            continue;
        }
        const std::string key = pngKeyword(textKey(name));
        if (key.empty()) {
            metadata.left_out.push_back("the text attribute \"" + name + "\" (no letters for a PNG keyword)");
            continue;
        }
        texts.push_back({"tEXt", key + '\0' + text});
    }
    if (time) chunks.push_back(*time);
    chunks.insert(chunks.end(), texts.begin(), texts.end());
    return metadata;
}

}  // namespace ddt
