#include "png_metadata.h"

#include <OpenImageIO/strutil.h>
#include <OpenImageIO/tiffutils.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <optional>

namespace ddt {

namespace {

namespace Strutil = OIIO::Strutil;

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

ColourSpace colourSpace(const OIIO::ImageSpec& spec, std::vector<std::string>& left_out) {
    ColourSpace result;
    const OIIO::string_view name = spec.get_string_attribute("oiio:ColorSpace");
    float display_gamma = 0;
    if (Strutil::iequals(name, "Linear")) {
        display_gamma = 1.0f;
    } else if (Strutil::istarts_with(name, "Gamma")) {
        display_gamma = spec.get_float_attribute("oiio:Gamma", 1.0f);
        OIIO::string_view number = name;
        Strutil::parse_word(number);
        const float stated = Strutil::from_string<float>(number);
        if (stated >= 0.01f && stated <= 10.0f) display_gamma = stated;
    } else if (Strutil::iequals(name, "sRGB")) {
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

std::optional<PngChunk> iccChunk(const OIIO::ImageSpec& spec, std::vector<std::string>& left_out) {
    const OIIO::ParamValue* icc = spec.find_attribute("ICCProfile");
    if (!icc || icc->type().size() == 0) return std::nullopt;
    const auto* profile = static_cast<const uint8_t*>(icc->data());
    const size_t size = icc->type().size();
    if (std::string problem = iccProblem(profile, size, spec.nchannels); !problem.empty()) {
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

// The eXIf chunk (little-endian TIFF data: OpenImageIO 2.4 writes a wrong signature for big
// endian), when the spec holds EXIF or GPS attributes.
std::optional<PngChunk> exifChunk(const OIIO::ImageSpec& spec) {
    bool any = false;
    for (const OIIO::ParamValue& p : spec.extra_attribs)
        any = any || Strutil::istarts_with(p.name(), "Exif:") || Strutil::istarts_with(p.name(), "GPS:");
    if (!any) return std::nullopt;
    std::vector<char> blob;
    OIIO::encode_exif(spec, blob, OIIO::endian::little);
    return PngChunk{"eXIf", std::string(blob.begin(), blob.end())};
}

// The oFFs chunk: the image's offset in pixels, which OpenImageIO always writes.
PngChunk offsetChunk(const OIIO::ImageSpec& spec) {
    return {"oFFs", bigEndian32(uint32_t(spec.x)) + bigEndian32(uint32_t(spec.y)) + std::string(1, '\0')};
}

// The pHYs chunk from XResolution, YResolution, ResolutionUnit and PixelAspectRatio, as
// OpenImageIO 2.4 computes it (in single precision, truncated): pixels per metre for inches,
// centimetres and metres, else unit 0 (only the aspect ratio means something). A missing
// resolution follows the other and the aspect ratio, or is 100.
std::optional<PngChunk> resolutionChunk(const OIIO::ImageSpec& spec, std::vector<std::string>& left_out) {
    const OIIO::string_view unit = spec.get_string_attribute("ResolutionUnit");
    float x = spec.get_float_attribute("XResolution"), y = spec.get_float_attribute("YResolution");
    const float aspect = spec.get_float_attribute("PixelAspectRatio");
    if (!x && !y && !aspect && unit.empty()) return std::nullopt;
    bool metric = false;
    float scale = 1;
    if (Strutil::iequals(unit, "meter") || Strutil::iequals(unit, "m")) {
        metric = true;
    } else if (Strutil::iequals(unit, "cm")) {
        metric = true;
        scale = 100;
    } else if (Strutil::iequals(unit, "inch") || Strutil::iequals(unit, "in")) {
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

// The tIME chunk from a DateTime that reads as "YYYY:MM:DD HH:MM:SS" (or with - or / in the
// date); OpenImageIO drops any other.
std::optional<PngChunk> timeChunk(const std::string& date_time) {
    int year, month, day, hour, minute, second;
    if (!Strutil::scan_datetime(date_time, year, month, day, hour, minute, second) || year < 0 || year > 65535)
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
    if (Strutil::iequals(name, "Artist")) return "Author";
    if (Strutil::iequals(name, "name") || Strutil::iequals(name, "DocumentName")) return "Title";
    if (Strutil::iequals(name, "description") || Strutil::iequals(name, "ImageDescription")) return "Description";
    return name;
}

// Attributes stored otherwise (pHYs), or not at all.
bool storedApart(const std::string& name) {
    for (const char* apart : {"planarconfig", "compression", "ResolutionUnit", "XResolution", "YResolution"})
        if (Strutil::iequals(name, apart)) return true;
    return false;
}

}  // namespace

PngMetadata pngMetadata(const OIIO::ImageSpec& spec) {
    PngMetadata metadata;
    std::vector<PngChunk>& chunks = metadata.chunks;
    const ColourSpace colour = colourSpace(spec, metadata.left_out);
    const std::optional<PngChunk> icc = iccChunk(spec, metadata.left_out);
    // libpng's order; with an ICC profile the sRGB chunk gives way to it.
    if (colour.gamma) chunks.push_back({"gAMA", bigEndian32(*colour.gamma)});
    if (icc) chunks.push_back(*icc);
    else if (colour.srgb) chunks.push_back({"sRGB", std::string(1, '\3')});  // rendering intent: absolute colorimetric
    if (colour.srgb) chunks.push_back({"cHRM", srgbChromaticities()});
    if (std::optional<PngChunk> exif = exifChunk(spec)) chunks.push_back(*exif);
    chunks.push_back(offsetChunk(spec));
    if (std::optional<PngChunk> resolution = resolutionChunk(spec, metadata.left_out)) chunks.push_back(*resolution);

    std::optional<PngChunk> time;
    std::vector<PngChunk> texts;
    for (const OIIO::ParamValue& p : spec.extra_attribs) {
        const std::string name = p.name().string();
        if (storedApart(name) || p.type() != OIIO::TypeDesc::STRING) continue;
        // A ustring's characters; OpenImageIO keeps "" as a null pointer.
        const char* characters = *static_cast<const char* const*>(p.data());
        const std::string text = characters ? characters : "";
        if (Strutil::iequals(name, "DateTime")) {
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
